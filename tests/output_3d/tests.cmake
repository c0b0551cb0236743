# Issue 12, 3D output, loads, detachment, restart, images and the 3D cases
# (io3d; tests/output_3d/*.prm explain each closed form; references written
# by hand). Simple shear u = (z, 0, 0) in a 2 × 1 × 1 box: wall shear
# stress, interface traction, von Mises √3 σ_xz (0 by the 2D formula) and
# the total forces on all six faces; probes with z and w; the snapshot's
# velocity, vorticity vector (0, 1, 0), divergence and pressure.
set(_shear_3d_forces)
foreach(_face Front Back Inlet Outlet Bottom Top)
  foreach(_d x y z)
    list(APPEND _shear_3d_forces force_${_d}_${_face})
  endforeach()
endforeach()
string(REPLACE ";" "," _shear_3d_forces "${_shear_3d_forces}")
viscofilm_test(shear_3d MODE run RANKS 1 2
  PRM ${S}/output_3d/shear_3d.prm
  NUMDIFF "-a 1e-8 -r 0"
  COMPARE statistics.csv:step,wall_shear_stress_mean,wall_shear_stress_max,interface_traction_mean,interface_traction_max,von_mises_max,detachment_area,${_shear_3d_forces}
          probes.csv:step,x,y,z,u,v,w,p,volume_fraction)
viscofilm_test(shear_3d_fields MODE fields RANKS 1 2
  PRM ${S}/output_3d/shear_3d.prm
  REFERENCE unused
  TOLERANCE 1e-6
  EXACT "velocity[0]=z" "velocity[1]=0" "velocity[2]=0"
        "vorticity[0]=0" "vorticity[1]=1" "vorticity[2]=0"
        "divergence=0" "pressure=0" "von_mises=3**0.5")

# The six stress components in their order (xx, xy, xz, yy, yz, zz), each a
# different linear function, through probes.csv and the snapshot's tau_*.
viscofilm_test(stress_fields_3d MODE run RANKS 1 2
  PRM ${S}/output_3d/stress_fields_3d.prm
  NUMDIFF "-a 1e-12 -r 0"
  COMPARE probes.csv:step,x,y,z,u,v,w,p,volume_fraction,tau_xx,tau_xy,tau_xz,tau_yy,tau_yz,tau_zz)
viscofilm_test(stress_fields_3d_snapshot MODE fields RANKS 1 2
  PRM ${S}/output_3d/stress_fields_3d.prm
  REFERENCE unused
  TOLERANCE 1e-6
  EXACT "tau_xx=x" "tau_xy=y" "tau_xz=z" "tau_yy=1 + x" "tau_yz=2 + y" "tau_zz=3 + z")

# Detachment by von Mises in 3D Couette flow across the channel (σ_yz = 1):
# the whole layer goes at the first step, 1e-7 above the threshold.
viscofilm_test(detachment_couette_3d MODE run RANKS 1 2
  PRM ${S}/output_3d/detachment_couette_3d.prm
  NUMDIFF "-a 1e-10 -r 0"
  COMPARE statistics.csv:step,volume_fraction_integral,detached_mass,detached_mass_total,detached_y_min,detached_y_max)

# φ from a 3D TIFF stack through the 3D program, on a mesh adapted to it
# (the biofilm indicator and the image's pixels): the half-ball on the
# bottom wall (tests/output_3d/half_ball_3d.prm). ∫φ equals the voxels'
# 0.00345 to the mesh's interpolation error (measured 0.27 %, bound 1 %),
# the first page is
# the lowest slice (φ = 0.1 at y = 0.025, 0 at y = 0.225 beside the axis),
# and the ball is centred at (0.5, 0, 0.5) (φ > 0 at (0.5, 0.2, 0.5), 0 at
# (0.5, 0.3, 0.5)).
viscofilm_test(half_ball_3d MODE run RANKS 1 2
  PRM ${S}/output_3d/half_ball_3d.prm
  DATA ${S}/image/half_ball_stack.tif
  BOUND "statistics.csv:volume_fraction_integral>0.0034155"
        "statistics.csv:volume_fraction_integral<0.0034845"
        "probes.csv[y<0.21]:volume_fraction>0.09"
        "probes.csv[y>0.2]:volume_fraction<0.01"
  NUMDIFF "-a 1e-12 -r 1e-9"
  COMPARE statistics.csv:step,cells,volume_fraction_integral
          probes.csv:step,x,y,z,volume_fraction)
