# Command-line behaviour of orbit, continue, lyapunov and basins: exit codes, messages naming the flag,
# the files written (run_cli_test.sh does the checks).
if(NOT TARGET impactlab)
  return()
endif()

foreach(cmd orbit continue lyapunov basins)
  impactlab_cli_test(help_${cmd} --rc 0 --match "usage: impactlab ${cmd}" -- ${cmd} --help)
endforeach()
impactlab_cli_test(orbit_period1 --rc 0 --match "Floquet multipliers" --match "stable: yes"
                   --csv orbit.csv "t,x,v,phi" 600 700
                   -- orbit --model A1C --omega 10 --out orbit.csv)
# The help states the analysis default rtol (1e-10), and a looser --rtol still converges (Newton asks only
# for what the integrator can give).
impactlab_cli_test(help_continue_rtol --rc 0 --match "default 1e-10 here" -- continue --help)
impactlab_cli_test(orbit_rtol_loose --rc 0 --match "Floquet multipliers" -- orbit --model A1C --omega 10.5 --rtol 1e-8 --out orbit.csv)
impactlab_cli_test(orbit_missing_omega --rc 2 --match "'--omega'" -- orbit --model A1C --out orbit.csv)
impactlab_cli_test(orbit_bad_from --rc 2 --match "'--from'" -- orbit --model A1C --omega 10 --from 1 --out o.csv)
impactlab_cli_test(continue_short --rc 0 --match "period_doubling +omega = 10.86"
                   --csv out/branches.csv "branch,omega,x,v,period,stable" 3 1000
                   -- continue --model A1C --omega-min 10 --omega-max 11.5 --max-period 1 --out out)
# A special point met from several branches or phases of one orbit is listed once (A3C's doubling at
# 18.4466542 was listed three times, its grazing at 16.5239088 twice).
impactlab_cli_test(continue_points_once --rc 0 --count "period_doubling +omega = 18\\.4466" 1 --count "grazing +omega = 16\\.5239" 1
                   -- continue --model A3C --omega-min 8 --omega-max 25 --omega-start 9 --out out)
# A3C's continuation over 8..25 takes about 22 s of CPU; on a 2-core machine shared with other jobs its wall
# time passed the default 60 s.
set_tests_properties(cli.continue_points_once PROPERTIES TIMEOUT 180)
# A1C's cascade from its period-1 doubling at 22.147 down to period 16, with Feigenbaum's ratios printed.
impactlab_cli_test(continue_cascade --rc 0 --match "cascade: doublings of period 1 at 22.147.* 16 at 19.4212"
                   --match "cascade: ratios .* 4\\.[5-7][0-9]+ 4\\.[5-7][0-9]+ \\(Feigenbaum's delta 4.6692\\)"
                   -- continue --model A1C --omega-min 19.38 --omega-max 22.6 --omega-start 22.6 --max-period 16 --out out)
set_tests_properties(cli.continue_cascade PROPERTIES TIMEOUT 180)
# Benettin 1.59 +- 0.05, two trajectories 1.50 +- 0.07 1/s: a difference of 0.09 +- 0.09, well within 3 standard errors.
impactlab_cli_test(lyapunov_check_scatter --rc 0 --match "check at rtol 1e-11: Benettin .* \\+- .* two trajectories"
                   --match "check: they agree within their scatter"
                   -- lyapunov --model A1C --omega 16 --check)
impactlab_cli_test(continue_bad_param --rc 2 --match "'--param'" -- continue --param bogus --out out)
impactlab_cli_test(continue_inverted --rc 2 --match "--omega-max" -- continue --omega-min 12 --omega-max 11 --out out)
impactlab_cli_test(lyapunov_one --rc 0 --match "lambda_max = " -- lyapunov --model A1G --omega 16 --periods 100)
impactlab_cli_test(lyapunov_missing_omega --rc 2 --match "'--omega'" -- lyapunov --model A1G)
impactlab_cli_test(lyapunov_sweep_bogus --rc 2 --match "'--sweep'" -- lyapunov --sweep sideways --out l.csv)
impactlab_cli_test(basins_tiny --rc 0 --match "^label,kind,period,well,x,v,cells,fraction" --match "[0-9]+,(period|chaos),"
                   --csv basins.csv "x0,v0,label" 16 16
                   -- basins --model A1G --omega 13 --grid 4 --threads 2 --out basins.csv --png basins.png)
impactlab_cli_test(basins_bad_grid --rc 2 --match "'--grid'" -- basins --model A1G --omega 13 --grid 0 --out b.csv)
impactlab_cli_test(basins_grid_not_integer --rc 2 --match "'--grid'" -- basins --model A1G --omega 13 --grid 4x4 --out b.csv)
impactlab_cli_test(basins_missing_omega --rc 2 --match "'--omega'" -- basins --model A1G --grid 4 --out b.csv)
impactlab_cli_test(basins_bad_range --rc 2 --match "'--x-range'" -- basins --omega 13 --grid 4 --x-range 0.01:-0.01 --out b.csv)
impactlab_cli_test(basins_range_no_colon --rc 2 --match "'--v-range'" -- basins --omega 13 --grid 4 --v-range 0.3 --out b.csv)
impactlab_cli_test(basins_png_unwritable --rc 2 --match "--png: cannot write" --no-match "basins A1G"
                   -- basins --omega 13 --grid 4 --out b.csv --png /nonexistent_dir/b.png)
# A1G at xI = -4 mm: the grazing is a nonsmooth fold (free and impacting branch meet there); the impacting
# branch's own turn at 9.548943 is a smooth fold, named apart.
impactlab_cli_test(continue_nonsmooth_and_smooth_fold --rc 0 --match "grazing at omega = 9\\.6004962.*: nonsmooth fold"
                   --match "the impacting branch then turns at omega = 9\\.54894.*, a smooth fold"
                   -- continue --model A1G --xI -0.004 --omega-min 8 --omega-max 14 --omega-start 9 --max-period 1 --out c)
# H's map jumps at a grazing: the free branch ends there and the impacting branch starts apart, at the orbit
# that arrives at rest (A1H's period 2 at 12.665).
impactlab_cli_test(continue_h_dwell --rc 0 --match "grazing at omega = 12\\.7992694: dwell at rest"
                   --match "starts at omega = 12\\.66521"
                   -- continue --model A1H --omega-min 12 --omega-max 16.5 --omega-start 12.7 --period 2 --max-period 2 --out c)
# A1G's fold curve, followed down in xI from -4 mm, is lost where it runs into the grazing: the end says so.
impactlab_cli_test(scan_fold_curve_meets_grazing --rc 0
                   --match "fold lost near xI = -0\\.004[56][0-9]+ \\(its last orbit's slowest impact is [0-9.e-]+ m/s: it runs into the grazing"
                   -- scan --model A1G --xI -0.004 --x omega:8.5:11:3 --y xI:-0.008:-0.002:3 --measure period --out pl.csv
                      --curves-out curves.csv --fold-from 9.548943,-0.0157368,0.00230387)
