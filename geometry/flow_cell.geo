// A microfluidic channel with a pillar, in metres: 200 µm wide, a pillar of
// radius 25 µm in its middle, 0.5 mm of channel upstream and 1.5 mm
// downstream of the pillar (the streamer set-up of Rusconi et al. 2010, a
// biofilm on a pillar in a flow of water). prm/examples/pillar-streamer.prm
// uses it; geometry/make_meshes.sh writes flow_cell.msh.
Xin = -0.5e-3;  Xout = 1.5e-3;  Yc = 100e-6;  H = 100e-6;  R = 25e-6;
Obstacle = "Pillar";
// the pillar's wake, where a streamer grows, is resolved by small cells
// near the pillar (radial ratio 1.12) that grow slowly downstream (1.04)
Na = 9;  Nr = 9;  Nup = 13;  Ndown = 41;  Gr = 1.12;  Gx = 1.04;
Include "channel_with_obstacle.geo";
