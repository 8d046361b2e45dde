# Per-case tolerances of the YADE cross-check gates (validation/gates/CMakeLists.txt, label `yade`)
# where the default ASPERITY_YADE_TOL does not hold for a stated, measured reason
# (docs/crosscheck.md, "Systematic differences"). Set ASPERITY_YADE_TOL_<test name without "yade.">.

# Chung & Ooi tests 6 and 8 with fast contact-point slip (chi <= 4.51, slip 0.09-2.2 m/s) and
# e = 0.5: YADE adds its shear dashpot c_s v_s outside the Coulomb cap while the spring is still
# below mu F_n, so the first steps of contact carry tangential spikes of up to ~2.4 times the
# normal force (asperity caps spring + dashpot at mu F_n). Measured (reports/yade/crosscheck.md):
# peak force up to 67 %, impulse up to 6.5 % apart, contact duration within 5e-4. 0.7 bounds the
# peak-force difference this design choice produces; the duration and rebound agree far closer.
foreach(material al_alloy_t6 nylon)
  foreach(chi 00.187 00.358 00.551 00.765 00.979 01.214 01.490 02.090 02.990 04.510)
    set(ASPERITY_YADE_TOL_chung_ooi.chung-ooi-t6-${material}-chi${chi} 0.7)
    set(ASPERITY_YADE_TOL_chung_ooi.chung-ooi-t8-${material}-chi${chi} 0.7)
  endforeach()
endforeach()

# Damped Hertz impacts (validation/cases/restitution, hertz law): asperity's dashpot sees the
# predicted end-of-step velocity v_{n+1/2} + dt a_n / 2, YADE's the half-step velocity; the two
# differ by dt a / 2, which moves the damped peak force by up to 0.27 % at e = 0.1 (the largest
# damping) and less as e rises (0.12 % at e = 0.5, 0.02 % at e = 0.9; impulse and duration within
# 0.13 %). 0.5 % bounds that measured difference.
foreach(geometry plane sphere)
  foreach(e 0.1 0.3 0.5 0.7 0.9)
    set(ASPERITY_YADE_TOL_restitution.restitution-hertz-sphere-${geometry}-e${e} 0.005)
  endforeach()
endforeach()
