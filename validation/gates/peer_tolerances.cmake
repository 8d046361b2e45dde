# Tolerances and refusals of the LAMMPS and LIGGGHTS gates (validation/gates/CMakeLists.txt), each
# with its measured reason (docs/crosscheck.md; figures from validation/report/peer_table.py).

# The CI subset: every geometry (sphere-sphere, sphere-plane, force recorded on the plane), law
# (hertz, hertz-mindlin, linear), damping, obliquity, spin and Chung & Ooi test.
set(ASPERITY_PEER_CI_CASES
  hertz.hertz-glass-sphere-plane-1ms hertz.hertz-glass-sphere-sphere-1ms
  hertz.hertz-steel-sphere-plane-10ms hertz.hertz-polymer-sphere-sphere-0.1ms
  record.record-on-plane-normal record.record-on-plane-oblique
  restitution.restitution-hertz-sphere-plane-e0.5 restitution.restitution-hertz-sphere-sphere-e0.3
  restitution.restitution-linear-sphere-plane-e0.1 restitution.restitution-linear-sphere-sphere-e0.7
  chung_ooi.chung-ooi-t1-glass chung_ooi.chung-ooi-t2-al_alloy chung_ooi.chung-ooi-t3-cast_iron-e0.6
  chung_ooi.chung-ooi-t4-al_oxide-05deg chung_ooi.chung-ooi-t4-al_oxide-45deg
  chung_ooi.chung-ooi-t5-steel-psi02.0 chung_ooi.chung-ooi-t5-polyethylene-psi10.0
  chung_ooi.chung-ooi-t6-al_alloy_t6-chi00.187 chung_ooi.chung-ooi-t6-nylon-chi11.900
  chung_ooi.chung-ooi-t7-al_alloy_t6-w03.4641 chung_ooi.chung-ooi-t8-al_alloy_t6-chi00.358
  chung_ooi.chung-ooi-t8-nylon-chi07.840)

# Default 0.3 %: elastic impacts agree to round-off (≤ 3e-14, same force law, same velocity-Verlet
# positions); damped ones differ by asperity's dashpot velocity (predicted end of step; LAMMPS and
# LIGGGHTS use the half-step velocity), measured up to 2.5e-3 (Hertz e = 0.3 sphere-sphere peak).
set(ASPERITY_lammps_TOL 0.003)
set(ASPERITY_liggghts_TOL 0.003)
# LIGGGHTS's tangential spring is k_t(δ) times the total tangential displacement, asperity's (and
# LAMMPS mindlin/force's) is incremental: oblique elastic impacts differ by up to 3.0e-3 (Chung &
# Ooi test 5, steel, ψ = 2).
foreach(case chung_ooi.chung-ooi-t5-steel-psi02.0 record.record-on-plane-oblique
        chung_ooi.chung-ooi-t4-al_oxide-05deg chung_ooi.chung-ooi-t8-nylon-chi07.840)
  set(ASPERITY_liggghts_TOL_${case} 0.005)
endforeach()
# Chung & Ooi tests 6 and 8 with fast slip and e = 0.5: LIGGGHTS, like YADE, adds the shear dashpot
# outside the Coulomb cap while the spring is small: peak force up to 65 %, impulse 4.4 % apart
# (duration within 4e-4); the same bound as the YADE gates (yade_tolerances.cmake).
foreach(material al_alloy_t6 nylon)
  foreach(chi 00.187 00.358 00.551 00.765 00.979 01.214 01.490 02.090 02.990 04.510)
    set(ASPERITY_liggghts_TOL_chung_ooi.chung-ooi-t6-${material}-chi${chi} 0.7)
    set(ASPERITY_liggghts_TOL_chung_ooi.chung-ooi-t8-${material}-chi${chi} 0.7)
  endforeach()
endforeach()

# Refused, with the reason the test expects on stderr:
# - boxes: the adapters map planes to fix wall/gran only;
# - LAMMPS: the Hertz damping ζ of e ≤ 0.2 exceeds what its Tsuji map α(e) reaches (1.2728);
# - LIGGGHTS: ζ of e = 0.1 and 0.2 exceeds √5|β| at its smallest accepted e (0.05): 1.543.
foreach(peer lammps liggghts)
  foreach(case record.record-on-box-normal record.record-on-box-oblique)
    list(APPEND ASPERITY_${peer}_REFUSED ${case})
    set(ASPERITY_${peer}_REFUSED_${case} "shape: ${peer}: a box is not mapped")
  endforeach()
  foreach(case chung_ooi.chung-ooi-t3-al_oxide-e0.2 chung_ooi.chung-ooi-t3-cast_iron-e0.2
          restitution.restitution-hertz-sphere-plane-e0.1 restitution.restitution-hertz-sphere-sphere-e0.1)
    list(APPEND ASPERITY_${peer}_REFUSED ${case})
    set(ASPERITY_${peer}_REFUSED_${case} "restitution: ${peer}: .* need the Hertz damping")
  endforeach()
endforeach()
