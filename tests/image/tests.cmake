# Issue 14 item 1: φ from an image (Initial conditions/Volume fraction =
# image; images by geometry/make_images.py). The half-disc of radius 0.25
# on the bottom wall: ∫φ against the closed form 0.1 π R²/2 = 0.00981748
# and (binary images) the 988 biofilm pixels' 0.00988, at Δx = 1/64 with
# pixels of 0.01 (doc/images.md): 8-bit PNG anti-aliased with the linear
# map (closed form to 0.1 %), 16-bit PNG with a contrast only 16 bits carry
# and 16-bit big-endian TIFF, thresholded (pixels to 0.2 %, closed form to
# 1 %). Probes: φ = 0.1 inside at (0.5, 0.2), 0 above the disc at
# (0.5, 0.3) and beside it at (0.8, 0.05) (an upside-down image would fail).
foreach(_case png8 png16 tiff)
  if(_case STREQUAL png8)
    set(_image half_disc_8bit.png)
    set(_bounds "statistics.csv:volume_fraction_integral>0.00980766"
                "statistics.csv:volume_fraction_integral<0.00982730")
  else()
    if(_case STREQUAL png16)
      set(_image half_disc_16bit.png)
    else()
      set(_image half_disc_16bit.tif)
    endif()
    set(_bounds "statistics.csv:volume_fraction_integral>0.00986024"
                "statistics.csv:volume_fraction_integral<0.00989976"
                "statistics.csv:volume_fraction_integral>0.00971930"
                "statistics.csv:volume_fraction_integral<0.00991565")
  endif()
  viscofilm_test(image_half_disc_${_case} MODE run RANKS 1 2
    PRM ${S}/image/half_disc_${_case}.prm
    DATA ${S}/image/${_image}
    BOUND ${_bounds}
    NUMDIFF "-a 1e-12 -r 1e-9"
    COMPARE statistics.csv:step,cells,volume_fraction_integral
            probes.csv:step,x,y,volume_fraction)
endforeach()

# The initial refinement on the image's pixels (tests/image/filament.prm): a
# filament between φ's nodes of the initial mesh refines it to level 7;
# ∫φ = 0.1 × 0.02 × 0.3 within 5 % (0 if only φ's nodes are looked at).
viscofilm_test(image_filament MODE run RANKS 1 2
  PRM ${S}/image/filament.prm
  DATA ${S}/image/filament.png
  BOUND "statistics.csv:volume_fraction_integral>5.7e-4"
        "statistics.csv:volume_fraction_integral<6.3e-4"
  NUMDIFF "-a 1e-12 -r 1e-9"
  COMPARE statistics.csv:step,cells,volume_fraction_integral
          probes.csv:step,x,y,volume_fraction)
