// The confined-cylinder benchmark (Alves, Pinho & Oliveira 2001; Hulsen,
// Fattal & Kupferman 2005): a cylinder of radius R = 1 centred in a channel
// of half-height H = 2 (blockage R/H = 0.5), from x = -20 to x = 30.
// Dimensionless lengths (units of R). prm/cylinder.prm uses it with
// Geometry/Mesh = gmsh; geometry/make_meshes.sh writes cylinder.msh.
Xin = -20;  Xout = 30;  Yc = 0;  H = 2;  R = 1;
Obstacle = "Cylinder";
// coarse mesh: 32 cells around the cylinder, 6 across the gap to the wall;
// cells grow by 8 % per cell away from the cylinder, 12 % along the channel
Na = 9;  Nr = 7;  Nup = 17;  Ndown = 23;  Gr = 1.08;  Gx = 1.12;
Include "channel_with_obstacle.geo";
