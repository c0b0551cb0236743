// A channel with a circular obstacle, all quadrilaterals (transfinite and
// recombined), included by cylinder.geo and flow_cell.geo, which set first:
//   Xin, Xout     x of the inlet and the outlet
//   Yc, H         y of the obstacle's centre and the channel's half-height
//                 (the walls are y = Yc - H and y = Yc + H)
//   R             obstacle radius (< H); the centre is at x = 0
//   Obstacle      the obstacle's physical-group name
//   Na            nodes on each quarter of the obstacle (and on the walls of
//                 the box around it), Nr nodes from the obstacle to the box,
//                 Nup and Ndown nodes along the walls up- and downstream,
//   Gr, Gx        the size ratios of neighbouring cells from the obstacle
//                 outwards (radially, and along the channel)
// The box around the obstacle is the square [-H, H] x [Yc-H, Yc+H], cut into
// four patches by its diagonals. Physical groups (their tags become deal.II
// boundary ids): Inlet 1, Outlet 2, Bottom 3, Top 4, the obstacle 5, the
// fluid 6.

c = R / Sqrt(2);
Point(1) = {0, Yc, 0};                         // centre
Point(2) = { c, Yc - c, 0};                    // obstacle at -45°
Point(3) = { c, Yc + c, 0};                    //            45°
Point(4) = {-c, Yc + c, 0};                    //           135°
Point(5) = {-c, Yc - c, 0};                    //           225°
Point(6) = { H, Yc - H, 0};                    // box corners
Point(7) = { H, Yc + H, 0};
Point(8) = {-H, Yc + H, 0};
Point(9) = {-H, Yc - H, 0};
Point(10) = {Xin, Yc - H, 0};                  // inlet
Point(11) = {Xin, Yc + H, 0};
Point(12) = {Xout, Yc - H, 0};                 // outlet
Point(13) = {Xout, Yc + H, 0};

Circle(1) = {2, 1, 3};                         // obstacle arcs (right, top, left, bottom)
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Line(5) = {2, 6};                              // diagonals, from the obstacle out
Line(6) = {3, 7};
Line(7) = {4, 8};
Line(8) = {5, 9};
Line(9) = {6, 7};                              // box: right, top, left, bottom
Line(10) = {7, 8};
Line(11) = {8, 9};
Line(12) = {9, 6};
Line(13) = {9, 10};                            // upstream walls, from the box out
Line(14) = {8, 11};
Line(15) = {10, 11};                           // inlet
Line(16) = {6, 12};                            // downstream walls, from the box out
Line(17) = {7, 13};
Line(18) = {12, 13};                           // outlet

Transfinite Curve{1, 2, 3, 4, 9, 10, 11, 12, 15, 18} = Na;
Transfinite Curve{5, 6, 7, 8} = Nr Using Progression Gr;
Transfinite Curve{13, 14} = Nup Using Progression Gx;
Transfinite Curve{16, 17} = Ndown Using Progression Gx;

Curve Loop(1) = {1, 6, -9, -5};   Plane Surface(1) = {1};   // right patch
Curve Loop(2) = {2, 7, -10, -6};  Plane Surface(2) = {2};   // top
Curve Loop(3) = {3, 8, -11, -7};  Plane Surface(3) = {3};   // left
Curve Loop(4) = {4, 5, -12, -8};  Plane Surface(4) = {4};   // bottom
Curve Loop(5) = {13, 15, -14, 11}; Plane Surface(5) = {5};  // upstream
Curve Loop(6) = {16, 18, -17, -9}; Plane Surface(6) = {6};  // downstream

Transfinite Surface{1} = {2, 3, 7, 6};
Transfinite Surface{2} = {3, 4, 8, 7};
Transfinite Surface{3} = {4, 5, 9, 8};
Transfinite Surface{4} = {5, 2, 6, 9};
Transfinite Surface{5} = {9, 10, 11, 8};
Transfinite Surface{6} = {6, 12, 13, 7};
Recombine Surface{1:6};

Physical Curve("Inlet", 1) = {15};
Physical Curve("Outlet", 2) = {18};
Physical Curve("Bottom", 3) = {13, 12, 16};
Physical Curve("Top", 4) = {14, 10, 17};
Physical Curve(Str(Obstacle), 5) = {1, 2, 3, 4};
Physical Surface("Fluid", 6) = {1:6};
