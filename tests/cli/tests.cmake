# Command-line behaviour of the impactlab program: exit codes (0 success, 1 runtime failure, 2 usage error),
# error messages that name the culprit, and the files a run writes. Each test runs the program once in a
# scratch directory through run_cli_test.sh (see there for the checks).
if(NOT TARGET impactlab)
  return()
endif()

set(IMPACTLAB_CLI_DRIVER ${CMAKE_CURRENT_LIST_DIR}/run_cli_test.sh)

# impactlab_cli_test(NAME CHECKS... -- ARGS...)
function(impactlab_cli_test name)
  add_test(NAME cli.${name} COMMAND bash ${IMPACTLAB_CLI_DRIVER} $<TARGET_FILE:impactlab> ${ARGN})
  set_tests_properties(cli.${name} PROPERTIES LABELS cli TIMEOUT 60)
endfunction()

# --- the command table -----------------------------------------------------------------------------------
impactlab_cli_test(no_command --rc 2 --match "usage: impactlab COMMAND" --)
impactlab_cli_test(help --rc 0 --match "commands:" --match "simulate" --match "bifurcation" -- --help)
impactlab_cli_test(unknown_command --rc 2 --match "unknown command 'frobnicate'" -- frobnicate)
foreach(cmd models simulate poincare bifurcation figure3)
  impactlab_cli_test(help_${cmd} --rc 0 --match "usage: impactlab ${cmd}" -- ${cmd} --help)
endforeach()
impactlab_cli_test(help_short_flag --rc 0 --match "usage: impactlab poincare" -- poincare -h)

# --- flags -----------------------------------------------------------------------------------------------
impactlab_cli_test(unknown_flag --rc 2 --match "unknown option '--frobnicate'"
                   -- simulate --omega 18 --duration 2 --out x.csv --frobnicate 3)
impactlab_cli_test(unknown_short_flag --rc 2 --match "unknown option '-q'"
                   -- poincare --omega 18 --periods 5 --out x.csv -q)
impactlab_cli_test(non_numeric_value --rc 2 --match "'--omega'" --match "'abc' is not a finite number"
                   -- simulate --omega abc --duration 2 --out x.csv)
impactlab_cli_test(trailing_garbage_value --rc 2 --match "'--duration'" --match "'2s'"
                   -- simulate --omega 18 --duration 2s --out x.csv)
impactlab_cli_test(non_integer_value --rc 2 --match "'--periods'" --match "not an integer"
                   -- poincare --omega 18 --periods 2.5 --out x.csv)
impactlab_cli_test(value_out_of_range --rc 2 --match "'--omega'" --match "outside"
                   -- simulate --omega -5 --duration 2 --out x.csv)
impactlab_cli_test(infinite_value --rc 2 --match "'--rtol'" -- simulate --omega 18 --duration 2 --rtol inf --out x.csv)
impactlab_cli_test(flag_without_value --rc 2 --match "'--out' needs a value" -- simulate --omega 18 --duration 2 --out)
impactlab_cli_test(flag_twice --rc 2 --match "'--omega' given twice"
                   -- simulate --omega 18 --omega 19 --duration 2 --out x.csv)
impactlab_cli_test(sweep_bogus --rc 2 --match "'--sweep'" --match "bogus" --absent d.csv
                   -- bifurcation --sweep bogus --out d.csv)
impactlab_cli_test(omega_range_inverted --rc 2 --match "--omega-max"
                   -- bifurcation --sweep up --omega-min 6 --omega-max 5 --steps 2 --out d.csv)

# --- required flags --------------------------------------------------------------------------------------
impactlab_cli_test(simulate_missing_out --rc 2 --match "'--out'" -- simulate --omega 18 --duration 2)
impactlab_cli_test(simulate_missing_omega --rc 2 --match "'--omega'" -- simulate --duration 2 --out x.csv)
impactlab_cli_test(simulate_missing_duration --rc 2 --match "'--duration'" -- simulate --omega 18 --out x.csv)
impactlab_cli_test(poincare_missing_out --rc 2 --match "'--out'" -- poincare --omega 18 --periods 5)
impactlab_cli_test(poincare_missing_periods --rc 2 --match "'--periods'" -- poincare --omega 18 --out x.csv)
impactlab_cli_test(bifurcation_missing_out --rc 2 --match "'--out'" -- bifurcation --sweep up --steps 2)
impactlab_cli_test(figure3_missing_out --rc 2 --match "'--out'" -- figure3 --steps 2)

# --- models and parameter files --------------------------------------------------------------------------
impactlab_cli_test(model_unknown --rc 2 --match "nonexistent" --match "A1C1"
                   -- simulate --model nonexistent --omega 18 --duration 2 --out x.csv)
impactlab_cli_test(model_bad_json_key --rc 2 --match "bad\\.json" --match "unknown key 'kappa'"
                   --write bad.json "{\"base\": \"A1H\", \"kappa\": 0.5}"
                   -- simulate --model bad.json --omega 18 --duration 2 --out x.csv)
impactlab_cli_test(model_bad_json_value --rc 2 --match "impact\\.kappa0"
                   --write bad.json "{\"base\": \"A1H\", \"impact\": {\"model\": \"H\", \"kappa0\": 1.5}}"
                   -- poincare --model bad.json --omega 18 --periods 5 --out x.csv)
impactlab_cli_test(model_bad_json_syntax --rc 2 --match "broken\\.json" --match "line 2, column"
                   --write broken.json "{\"base\": \"A1H\",\n  \"m\": }"
                   -- bifurcation --model broken.json --sweep up --steps 2 --out d.csv)
impactlab_cli_test(model_json_not_found --rc 2 --match "no_such_file\\.json"
                   -- simulate --model no_such_file.json --omega 18 --duration 2 --out x.csv)
# A non-finite number in a parameter file is a usage error (2) naming the file and the key.
impactlab_cli_test(model_json_non_finite --rc 2 --match "inf\\.json: line 1, column 26: key 'k': the number is out of range \\(not finite\\)"
                   --write inf.json "{\"base\": \"A1H\", \"k\": 1e999}"
                   -- simulate --model inf.json --omega 18 --duration 2 --out x.csv)
impactlab_cli_test(model_json_ok --rc 0 --csv x.csv "n,x,v" 3 3
                   --write ok.json "{\"base\": \"A1G\", \"name\": \"tilted\", \"xI\": 0.002}"
                   -- poincare --model ok.json --omega 18 --periods 3 --out x.csv)
impactlab_cli_test(xI_out_of_range --rc 2 --match "'--xI'" -- simulate --xI 0.2 --omega 18 --duration 2 --out x.csv)
impactlab_cli_test(models_list --rc 0 --match "A1C1" --match "kappa0" --match "constant_force" --match "cart_mass"
                   --match "bumper_offset" -- models)
impactlab_cli_test(models_json --rc 0 --match "\"model\": \"H\"" --match "\"kappa0\"" -- models --json A1H)
impactlab_cli_test(models_json_unknown --rc 2 --match "--json" --match "Q9" -- models --json Q9)

# --- output files ----------------------------------------------------------------------------------------
impactlab_cli_test(unwritable_out --rc nonzero --match "/nonexistent_dir_for_impactlab/x\\.csv"
                   -- simulate --model A1H --omega 18 --duration 0.01 --out /nonexistent_dir_for_impactlab/x.csv)
impactlab_cli_test(unwritable_out_bifurcation --rc nonzero --match "/nonexistent_dir_for_impactlab/d\\.csv"
                   -- bifurcation --sweep up --steps 2 --omega-min 5 --omega-max 6 --transient 1 --record 1
                      --out /nonexistent_dir_for_impactlab/d.csv)

# --- happy paths -----------------------------------------------------------------------------------------
impactlab_cli_test(simulate_csv --rc 0 --csv X.csv "t,x,v,phi,regime" 2000 2002 --match "X\\.csv"
                   -- simulate --model A1H --omega 18 --duration 2 --out X.csv)
impactlab_cli_test(simulate_negative_x0 --rc 0 --csv X.csv "t,x,v,phi,regime" 100 102
                   -- simulate --model A1C --omega 9 --duration 1 --dt 0.01 --x0 -0.011 --v0 -0.05 --out X.csv)
impactlab_cli_test(poincare_csv --rc 0 --csv P.csv "n,x,v" 5 5
                   -- poincare --model A1H --omega 18 --periods 5 --out P.csv)
impactlab_cli_test(poincare_phi0_csv --rc 0 --csv P.csv "n,x,v" 5 5
                   -- poincare --model A1H --omega 18 --periods 5 --phi0 2.5 --out P.csv)
impactlab_cli_test(poincare_phi0_above_2pi --rc 2 --match "'--phi0'" --match "outside \\[0, 6.28319\\]" --absent P.csv
                   -- poincare --omega 18 --periods 5 --phi0 7 --out P.csv)
impactlab_cli_test(poincare_phi0_negative --rc 2 --match "'--phi0'" --match "outside" --absent P.csv
                   -- poincare --omega 18 --periods 5 --phi0 -0.5 --out P.csv)
impactlab_cli_test(poincare_phi0_not_a_number --rc 2 --match "'--phi0'" --match "'90deg' is not a finite number"
                   -- poincare --omega 18 --periods 5 --phi0 90deg --out P.csv)
impactlab_cli_test(help_poincare_phi0 --rc 0 --match "--phi0 RAD" --match "phi = phi0 \\+ 2 pi \\(N \\+ n - 1\\) for phi0 > 0"
                   -- poincare --help)
add_test(NAME cli.poincare_phase COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/poincare_phase.sh $<TARGET_FILE:impactlab>)
set_tests_properties(cli.poincare_phase PROPERTIES LABELS cli TIMEOUT 120)
impactlab_cli_test(bifurcation_csv --rc 0 --csv B.csv "omega,x,v,period" 9 9
                   -- bifurcation --sweep up --steps 3 --omega-min 5 --omega-max 6 --transient 2 --record 3
                      --out B.csv)
# --settle 0: the paper's 20 + 70 periods alone, three columns; a level still in its transient (A1H at 18 rad/s,
# xI = 2.63 mm, which settles on a period 18 after about 3000 periods) reads -1, not settled, never chaos.
impactlab_cli_test(bifurcation_settle_off --rc 0 --csv B.csv "omega,x,v" 9 9 --no-match "levels:"
                   -- bifurcation --sweep up --steps 3 --omega-min 5 --omega-max 6 --transient 2 --record 3
                      --settle 0 --out B.csv)
impactlab_cli_test(bifurcation_not_settled --rc 0 --match "levels: [0-9]+ periodic, [1-9][0-9]* not settled"
                   --csv X.csv "xI,x,v,period" 1400 1400
                   -- bifurcation --model A1H --over xI --range 0:0.00263 --omega 18 --steps 20 --out X.csv)
impactlab_cli_test(bifurcation_ramp_csv --rc 0 --csv R.csv "omega,x,v" 9 9
                   -- bifurcation --model A1G --sweep ramp --omega-max 2 --ramp-time 60 --out R.csv)
# The CF sweep over xI or m0e at a fixed omega: the CSV's first column is the parameter, every error names
# its flag and the range that applies, and nothing is written.
impactlab_cli_test(bifurcation_over_xI --rc 0 --csv X.csv "xI,x,v,period" 6 6 --match "plot -> X\\.png"
                   -- bifurcation --model A1H --over xI --range -0.005:0.005 --omega 18 --steps 3 --transient 2
                      --record 2 --out X.csv --png X.png)
impactlab_cli_test(bifurcation_over_m0e_down --rc 0 --csv M.csv "m0e,x,v,period" 6 6
                   -- bifurcation --model A1G --sweep down --over m0e --range 0.01:0.03 --omega 12 --steps 2
                      --transient 2 --record 3 --out M.csv)
impactlab_cli_test(bifurcation_over_bogus --rc 2 --match "'--over'" --match "not one of omega, xI, m0e" --absent d.csv
                   -- bifurcation --over xi --range 0:0.01 --omega 18 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_xI_outside --rc 2 --match "--range: xI range -0\\.2\\.\\.0\\.01 m is outside \\[-0\\.1, 0\\.1\\] m"
                   --absent d.csv -- bifurcation --over xI --range -0.2:0.01 --omega 18 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_m0e_zero --rc 2 --match "--range: m0e range 0\\.\\.0\\.03 kg m is outside \\(0, 10. kg m"
                   --absent d.csv -- bifurcation --over m0e --range 0:0.03 --omega 18 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_xI_no_bumper --rc 2 --match "--over: xI: model A1none has no bumper" --absent d.csv
                   -- bifurcation --model A1none --over xI --range 0:0.01 --omega 18 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_xI_no_omega --rc 2 --match "--over xI needs the fixed forcing frequency --omega"
                   --absent d.csv -- bifurcation --over xI --range 0:0.01 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_xI_no_range --rc 2 --match "--over xI needs --range A:B \\[m\\]" --absent d.csv
                   -- bifurcation --over xI --omega 18 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_xI_range_reversed --rc 2 --match "'--range': the end is not above the start"
                   --absent d.csv -- bifurcation --over xI --range 0.01:0 --omega 18 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_xI_omega_min --rc 2 --match "--omega-min goes with --over omega" --absent d.csv
                   -- bifurcation --over xI --range 0:0.01 --omega 18 --omega-min 3 --steps 2 --out d.csv)
impactlab_cli_test(bifurcation_over_ramp --rc 2 --match "--over is for the CF sweeps" --absent d.csv
                   -- bifurcation --sweep ramp --over xI --range 0:0.01 --out d.csv)
impactlab_cli_test(bifurcation_omega_without_over --rc 2 --match "--omega is the fixed frequency of an xI or m0e sweep"
                   --absent d.csv -- bifurcation --omega 18 --steps 2 --out d.csv)
# --range over omega is --omega-min:--omega-max: the same file.
impactlab_cli_test(bifurcation_over_omega_range --rc 0 --csv W.csv "omega,x,v,period" 9 9
                   -- bifurcation --over omega --range 5:6 --steps 3 --transient 2 --record 3 --out W.csv)

# Every simulating command's --help should document the model flags it accepts (--model, --xI, --m0e,
# --rtol).
foreach(cmd simulate poincare bifurcation)
  impactlab_cli_test(help_${cmd}_model_flags --rc 0 --match "--rtol R" --match "--m0e M" -- ${cmd} --help)
endforeach()

# --- input-forced models, several runs, the recovery matrix ------------------------------------------------
set(_input_csv "t,x,u\n0,0,0\n0.001,0,1\n0.002,0,0\n0.003,0,-1\n0.004,0,0\n")
impactlab_cli_test(simulate_input --rc 0 --csv out.csv "t,x,v,u,regime" 4 6
                   --write duff.json "{\"base\": \"A1none\", \"m\": 1, \"m0e\": 0, \"k\": 100, \"c\": 1, \"T\": 0, \"a\": [0,0,0,0], \"b\": [0,0,0,0], \"input_gain\": 2}"
                   --write in.csv "${_input_csv}"
                   -- simulate --model duff.json --input in.csv --out out.csv)
impactlab_cli_test(simulate_input_flag_alone --rc 2 --match "--u-col needs --input" --absent out.csv
                   -- simulate --model A1H --omega 9 --duration 1 --u-col 2 --out out.csv)
impactlab_cli_test(simulate_input_without_u --rc 2 --match "no input column u" --match "x.csv"
                   --write x.csv "t,x,phi\n0,0,0\n0.001,0,0.1\n"
                   -- simulate --model A1H --input x.csv --out out.csv)
impactlab_cli_test(synth_input --rc 0 --match "5 samples over 0.004 s"
                   --write duff.json "{\"base\": \"A1none\", \"m\": 1, \"m0e\": 0, \"k\": 100, \"c\": 1, \"T\": 0, \"a\": [0,0,0,0], \"b\": [0,0,0,0], \"input_gain\": 2}"
                   --write in.csv "${_input_csv}"
                   -- synth --model duff.json --input in.csv --x0 0 --out du.csv)
impactlab_cli_test(synth_gain_without_input --rc 2 --match "--gain needs --input" -- synth --model A1H --gain 2 --out s.csv)
impactlab_cli_test(fit_test_rows_with_runs --rc 2 --match "--test-rows needs a single data file"
                   -- fit a.csv b.csv --model A1H --report r --test-rows 0:10)
impactlab_cli_test(help_recovery --rc 0 --match "usage: impactlab recovery" --match "--null" -- recovery --help)
impactlab_cli_test(recovery_bad_version --rc 2 --match "unknown model version 'A9Q'" -- recovery --versions A1C,A9Q)
impactlab_cli_test(fit_runs_short_one --rc 2 --match "a.csv: only 3 samples"
                   --write a.csv "t,x,phi\n0,0,0\n0.001,0,0.01\n0.002,0,0.02\n" --write b.csv "t,x,phi\n0,0,0\n0.001,0,0.01\n"
                   -- fit a.csv b.csv --model A1H --report r)

# --- files never clobbered, outputs checked before computing, errors that name the culprit ----------
set(_model_json "{\"base\": \"A1H\"}")
impactlab_cli_test(out_is_model_input --rc 2 --match "'model.json' is an input of this command" --unchanged model.json
                   --write model.json "${_model_json}"
                   -- simulate --model model.json --omega 10 --duration 1 --out model.json)
impactlab_cli_test(synth_out_is_model_input --rc 2 --match "is an input of this command" --unchanged m.json
                   --write m.json "${_model_json}" -- synth --model m.json --out m.json)
impactlab_cli_test(fit_report_holds_input --rc 2 --match "--report: './report.md' is an input" --unchanged report.md
                   --write report.md "t,x,phi" -- fit report.md --model A1H --report .)
impactlab_cli_test(bad_flag_keeps_old_output --rc 2 --match "'--rtol'" --unchanged k.csv --write k.csv "old"
                   -- simulate --model A1C --omega 10 --duration 1 --rtol 0 --out k.csv)
impactlab_cli_test(bad_steps_keeps_old_output --rc 2 --match "'--steps'" --unchanged d.csv --write d.csv "old"
                   -- bifurcation --steps 0 --out d.csv)
impactlab_cli_test(bad_x0_keeps_old_output --rc 2 --match "'--x0'" --unchanged p.csv --write p.csv "old"
                   -- poincare --omega 10 --periods 3 --x0 9 --out p.csv)
impactlab_cli_test(png_unwritable_before_computing --rc 2 --match "--png: cannot write '/nonexistent/b.png'" --absent d.csv
                   -- bifurcation --steps 2 --out d.csv --png /nonexistent/b.png)
impactlab_cli_test(figure3_unwritable --rc 2 --match "--out: cannot write '/nonexistent/f.png'" -- figure3 --out /nonexistent/f.png)
impactlab_cli_test(fit_report_unwritable --rc 2 --match "--report: cannot create the directory '/proc/x'" --absent d.csv.never
                   --write d.csv "t,x,phi" -- fit d.csv --model A1H --report /proc/x)
impactlab_cli_test(out_is_directory --rc 2 --match "is a directory, not a file name"
                   -- simulate --model A1C --omega 10 --duration 1 --out .)
impactlab_cli_test(stray_argument --rc 2 --match "unexpected argument 'stray'" --absent o.csv
                   -- simulate stray --model A1C --omega 1 --duration 1 --out o.csv)
impactlab_cli_test(json_duplicate_key --rc 2 --match "dup.json: key 'm' appears twice"
                   --write dup.json "{\"base\": \"A1H\", \"m\": 7, \"m\": 8}"
                   -- simulate --model dup.json --omega 1 --duration 1 --out o.csv)
impactlab_cli_test(json_unknown_stiffness --rc 2 --match "key 'stiffness': unknown label 'Z9'"
                   --write st.json "{\"base\": \"A1H\", \"stiffness\": \"Z9\"}"
                   -- simulate --model st.json --omega 1 --duration 1 --out o.csv)
impactlab_cli_test(json_magnitude --rc 2 --match "key 'm': must lie in \\[0.001, 10000\\] kg"
                   --write tiny.json "{\"base\": \"A1G\", \"m\": 1e-20}"
                   -- simulate --model tiny.json --omega 10 --duration 1 --out o.csv)
impactlab_cli_test(x_col_huge --rc 2 --match "column 99999999999999999999 names no column" --no-match "stol"
                   --write d.csv "t,x,phi\n0,0,0" -- fit d.csv --x-col 99999999999999999999 --report r)
impactlab_cli_test(synth_too_many_samples --rc 2 --match "more than 5e7" --no-match "bad_alloc"
                   -- synth --rate 1e7 --duration 1e6 --out s.csv)
impactlab_cli_test(synth_omega_cap --rc 2 --match "omega 1e\\+06 rad/s is outside \\[0, 1000\\]" -- synth --omega 1e6 --out s.csv)
set(_mm_csv "t,x,phi")   # 40 samples of a cart near x = -10 mm, written in mm
foreach(i RANGE 39)
  string(APPEND _mm_csv "\n${i}e-3,-10.${i},${i}e-2")
endforeach()
impactlab_cli_test(fit_mm_as_m --rc 2 --match "beyond the rail's travel" --match "--x-scale 1e-3" --absent r
                   --write mm.csv "${_mm_csv}" -- fit mm.csv --model A1H --report r)

# --- impactlab scan ------------------------------------------------------------------------------------------
add_test(NAME cli.scan_identity COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/scan_identity.sh $<TARGET_FILE:impactlab>)
set_tests_properties(cli.scan_identity PROPERTIES LABELS cli TIMEOUT 300)
impactlab_cli_test(scan_bad_axis --rc 2 --match "--x: 'omega:0:25'" --absent p.csv
                   -- scan --x omega:0:25 --y xI:-0.01:0.01:3 --out p.csv)
impactlab_cli_test(scan_same_axis --rc 2 --match "vary the same parameter"
                   -- scan --x omega:1:2:3 --y omega:3:4:3 --out p.csv)
impactlab_cli_test(scan_needs_omega --rc 2 --match "give --omega W"
                   -- scan --x xI:-0.01:0.01:3 --y m0e:0.01:0.03:3 --out p.csv)
impactlab_cli_test(scan_bad_measure --rc 2 --match "'colour'" -- scan --x omega:1:2:3 --y xI:0:0.01:2 --measure colour --out p.csv)
impactlab_cli_test(scan_small --rc 0 --csv p.csv "omega,m0e,period,impacts,xmin,xmax" 6 6
                   -- scan --model A1H --x omega:10:12:3 --y m0e:0.02:0.03:2 --measure period,impacts,xrange
                      --transient 5 --record 10 --threads 2 --out p.csv)
impactlab_cli_test(scan_doubling_needs_png --rc 2 --match "--doubling-from draws on the PNG" --absent p.csv
                   -- scan --model A1C --x omega:10.5:11:3 --y xI:-0.001:0:2 --doubling-from 10.8613339,-0.0142521,-0.0499209 --out p.csv)
impactlab_cli_test(scan_doubling_bad --rc 2 --match "expected OMEGA,X,V" --absent p.csv
                   -- scan --model A1C --x omega:10.5:11:3 --y xI:-0.001:0:2 --doubling-from 10.86,-0.014 --png p.png --out p.csv)
impactlab_cli_test(scan_doubling_curve --rc 0 --match "doubling curve: 3 points, ends: xI range / xI range" --csv p.csv "omega,xI,period" 6 6
                   -- scan --model A1C --x omega:10.5:11:3 --y xI:-0.001:0:2 --transient 2 --record 4 --threads 1
                      --doubling-from 10.8613339,-0.0142521,-0.0499209 --png p.png --out p.csv)
# A doubling of an impacting period-2 orbit (A1G's at 19.2312326, as continue prints it), followed in xI.
impactlab_cli_test(scan_doubling_impacting --rc 0 --match "doubling curve: 8 points, ends: xI range / xI range"
                   --csv p.csv "omega,xI,period" 9 9
                   -- scan --model A1G --x omega:18.9:19.5:3 --y xI:-0.0004:0.0004:3 --transient 2 --record 4 --threads 1
                      --doubling-from 19.2312326,-0.00537039,-0.0873334,2 --png p.png --out p.csv)
impactlab_cli_test(scan_doubling_bad_period --rc 2 --match "expected OMEGA,X,V\\[,K\\] with K in 1..64 \\(a doubling" --absent p.csv
                   -- scan --model A1G --x omega:18.9:19.5:3 --y xI:-0.0004:0.0004:3
                      --doubling-from 19.2312326,-0.00537039,-0.0873334,2.5 --png p.png --out p.csv)
impactlab_cli_test(scan_grazing_bad --rc 2 --match "expected OMEGA,X,V\\[,K\\]" --absent p.csv
                   -- scan --model A1G --xI -0.004 --x omega:9.5:9.7:3 --y xI:-0.0045:-0.004:2 --grazing-from 9.6,-0.0156,-0.0074,0.5
                      --png p.png --out p.csv)
impactlab_cli_test(scan_grazing_curve --rc 0 --match "grazing curve: 3 points, ends: xI range / xI range" --csv p.csv "omega,xI,period" 6 6
                   -- scan --model A1G --xI -0.004 --x omega:9.5:9.7:3 --y xI:-0.0045:-0.004:2 --transient 2 --record 4 --threads 1
                      --grazing-from 9.60049627,-0.0156163,-0.00744857 --png p.png --out p.csv)
# --curves-out: the grazing curve's points, for the visualiser's test (gui_plane_curves.sh reads them).
impactlab_cli_test(scan_curves_out --rc 0 --match "grazing curve: 3 points" --no-match "curves-out"
                   -- scan --model A1G --xI -0.004 --x omega:9.5:9.7:3 --y xI:-0.0045:-0.004:2 --transient 2 --record 4 --threads 1
                      --grazing-from 9.60049627,-0.0156163,-0.00744857 --png p.png --out p.csv --curves-out c.csv)
impactlab_cli_test(scan_grazing_fold_auto --rc 0 --match "grazing curve: started at the period-1 grazing at omega = 9.6004962"
                   --match "fold curve: started at the period-1 fold at omega = 9.5489430"
                   -- scan --model A1G --xI -0.004 --x omega:8.5:10.5:3 --y xI:-0.005:-0.004:2 --transient 2 --record 4 --threads 1
                      --grazing-from auto --fold-from auto --png p.png --out p.csv)
impactlab_cli_test(scan_curves_out_alone --rc 2 --match "--curves-out writes the continued curves" --absent p.csv
                   -- scan --model A1G --x omega:9.5:9.7:3 --y xI:-0.0045:-0.004:2 --out p.csv --curves-out c.csv)
# The curves' points alone, without a PNG to draw them on.
impactlab_cli_test(scan_fold_curve_points_only --rc 0 --match "fold curve: [1-9][0-9]* points" --csv p.csv "omega,xI,period" 6 6
                   -- scan --model A1G --xI -0.004 --x omega:9.4:9.6:3 --y xI:-0.0045:-0.004:2 --transient 2 --record 4 --threads 1
                      --fold-from 9.548943,-0.0157368,0.00230387 --curves-out c.csv --out p.csv)
impactlab_cli_test(scan_fold_curve --rc 0 --match "fold curve: [0-9]+ points, ends: xI range / xI range" --csv p.csv "omega,xI,period" 6 6
                   -- scan --model A1G --xI -0.004 --x omega:9.4:9.6:3 --y xI:-0.0045:-0.004:2 --transient 2 --record 4 --threads 1
                      --fold-from 9.548943,-0.0157368,0.00230387 --png p.png --out p.csv)

# --- every record of ../shared/data, fitted as a user would: never a crash, always an end -------------------
# (label shared-fit; run under the asan and ubsan presets by scripts/sanitize.sh as well)
set(IMPACTLAB_SHARED_FIT ${CMAKE_CURRENT_LIST_DIR}/shared_fit.sh)
set(IMPACTLAB_SHARED ${PROJECT_SOURCE_DIR}/../shared)
function(impactlab_shared_fit name)
  add_test(NAME shared_fit.${name} COMMAND bash ${IMPACTLAB_SHARED_FIT} $<TARGET_FILE:impactlab> ${IMPACTLAB_SHARED} -- ${ARGN})
  set_tests_properties(shared_fit.${name} PROPERTIES LABELS "cli;shared-fit" TIMEOUT 900 SKIP_RETURN_CODE 77)
endfunction()
foreach(f s1_quadratic_damping s2_bumper_offset s3_noise_only)
  impactlab_shared_fit(${f} @SHARED@/data/synthetic/${f}.csv.gz --model A1H)
endforeach()
foreach(f sym_left sym_right asym_left asym_right asym_left_stepped sym_chaos_hp0p5 sym_chaos_hp0p1 asym_chaos_hp0p5 asym_chaos_hp0p1)
  impactlab_shared_fit(${f} @SHARED@/data/mismatch/${f}.csv.gz --model duffing --u-col u)
endforeach()
impactlab_shared_fit(sym_pair @SHARED@/data/mismatch/sym_left.csv.gz @SHARED@/data/mismatch/sym_right.csv.gz --model duffing --u-col u)
impactlab_shared_fit(asym_pair @SHARED@/data/mismatch/asym_left.csv.gz @SHARED@/data/mismatch/asym_right.csv.gz --model duffing --u-col u)
impactlab_shared_fit(silverbox_snls @SHARED@/data/real/silverbox/SNLS80mV.csv.gz --model duffing --x-col V2 --u-col V1 --rate 610.3516)
impactlab_shared_fit(silverbox_schroeder @SHARED@/data/real/silverbox/Schroeder80mV.csv.gz --model duffing --x-col V2 --u-col V1 --rate 610.3516)
