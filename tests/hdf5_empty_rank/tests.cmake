# One coarse cell on two ranks: rank 1 owns no cells, which breaks deal.II
# 9.4.1's parallel HDF5 writer unless guarded. The snapshots must be complete.
viscofilm_test(hdf5_empty_rank MODE hdf5 RANKS 1 2
  PRM ${S}/hdf5_empty_rank/hdf5_empty_rank.prm
  NUMDIFF "-a 1e-12 -r 1e-8")
