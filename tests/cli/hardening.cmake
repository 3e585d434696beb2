# Command-line hardening: a failed or interrupted run never touches an existing output, outputs and inputs
# are bounded, input files are checked for kind and size first, contradictory flags are refused, and a
# message names the culprit with what it quotes cut and escaped (run_cli_test.sh does the checks).
if(NOT TARGET impactlab)
  return()
endif()

# --- a failure leaves old outputs as they were ------------------------------------------------------------
# (The message says Newton ran from the start and failed: a start refused before it would be exit status 2.)
impactlab_cli_test(orbit_failure_keeps_output --rc 1 --match "no period-1 orbit found from \\(0, 0\\): .* \\(residual [0-9.e+-]+\\)" --unchanged or.csv
                   --write or.csv "precious" -- orbit --model A1H --omega 1000 --out or.csv)
impactlab_cli_test(continue_failure_keeps_outputs --rc 1 --no-match "^branch 0"
                   --match "no period-7 orbit to continue: no periodic orbit of period 7 found at the start: Newton"
                   --mkdir cdir --write cdir/branches.csv "old branches" --write cdir/points.csv "old points"
                   --unchanged cdir/branches.csv --unchanged cdir/points.csv
                   -- continue --model A1C --period 7 --omega-min 14 --omega-max 15 --from 0.0,0.5 --out cdir)
add_test(NAME cli.signal_cleanup COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/signal_cleanup.sh $<TARGET_FILE:impactlab>)
set_tests_properties(cli.signal_cleanup PROPERTIES LABELS cli TIMEOUT 300)

# --- outputs bounded, named by the flags that multiply to them ---------------------------------------------
impactlab_cli_test(simulate_too_many_rows --rc 2 --match "--duration / --dt asks for 1e\\+13 output rows" --unchanged s.csv
                   --write s.csv "old" -- simulate --omega 18 --duration 1e6 --dt 1e-7 --out s.csv)
impactlab_cli_test(orbit_too_many_rows --rc 2 --match "--period x 2 pi / --omega / --dt asks for" --absent o.csv
                   -- orbit --omega 0.05 --period 64 --dt 1e-7 --out o.csv)
impactlab_cli_test(bifurcation_too_many_rows --rc 2 --match "--steps x --record asks for 1e\\+11" --no-match "bad_alloc"
                   --unchanged d.csv --write d.csv "old"
                   -- bifurcation --steps 100000 --record 1000000 --transient 0 --out d.csv)
impactlab_cli_test(ramp_too_many_rows --rc 2 --match "--omega-max x --ramp-time / 4 pi" --absent r.csv
                   -- bifurcation --sweep ramp --omega-max 1000 --ramp-time 1e6 --out r.csv)
impactlab_cli_test(scan_too_many_points --rc 2 --match "--x N x --y N asks for 1e\\+08" --absent p.csv
                   -- scan --x omega:1:2:100000 --y xI:0:0.01:1000 --out p.csv)

# --- input files: kind and size checked first, never a hang --------------------------------------------------
impactlab_cli_test(fit_directory --rc 2 --match "impactlab: error: dir: is a directory, not a file" --no-match "basic_filebuf"
                   --mkdir dir -- fit dir --model A1H --report r)
impactlab_cli_test(fit_fifo --rc 2 --match "f\\.csv: is a named pipe \\(FIFO\\)" --fifo f.csv -- fit f.csv --model A1H --report r)
impactlab_cli_test(fit_device --rc 2 --match "/dev/zero: is a device" --no-match "bad_alloc" -- fit /dev/zero --model A1H --report r)
impactlab_cli_test(fit_proc_mem --rc 2 --match "/proc/self/mem: cannot read it" --no-match "basic_filebuf"
                   -- fit /proc/self/mem --model A1H --report r)
impactlab_cli_test(fit_huge --rc 2 --match "s\\.csv: 2 GiB, more than the 1 GiB an input may hold" --sparse s.csv 2G
                   -- fit s.csv --model A1H --report r)
if(NOT IMPACTLAB_SANITIZE)
  add_test(NAME cli.gzip_bomb COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/gzip_bomb.sh $<TARGET_FILE:impactlab>)
  set_tests_properties(cli.gzip_bomb PROPERTIES LABELS cli TIMEOUT 120)
endif()
impactlab_cli_test(model_fifo --rc 2 --match "m\\.json: not a parameter file: is a named pipe" --fifo m.json
                   -- simulate --model m.json --omega 10 --duration 1 --out o.csv)
impactlab_cli_test(model_directory --rc 2 --match "m\\.json: not a parameter file: is a directory" --mkdir m.json
                   -- simulate --model m.json --omega 10 --duration 1 --out o.csv)
impactlab_cli_test(input_fifo --rc 2 --match "--input: u\\.csv: is a named pipe" --fifo u.csv
                   -- simulate --model A1H --input u.csv --out o.csv)

# --- scan --resume: the log's header and rows are checked ---------------------------------------------------
add_test(NAME cli.scan_resume COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/scan_resume.sh $<TARGET_FILE:impactlab>)
set_tests_properties(cli.scan_resume PROPERTIES LABELS cli TIMEOUT 300)

# --- parameters that pass their ranges but overflow ----------------------------------------------------------
impactlab_cli_test(model_b_overflow --rc 2 --match "b\\.json: key 'b': makes the denominator of F_SA overflow"
                   --write b.json "{\"base\": \"A3C\", \"b\": [1e308, 0, 0, 0]}"
                   -- simulate --model b.json --omega 10 --duration 1 --out o.csv)

# --- contradictory or duplicated inputs ------------------------------------------------------------------------
impactlab_cli_test(continue_min_without_param --rc 2 --match "--min belongs to --param xI or m0e"
                   -- continue --min 5 --max 10 --out c)
impactlab_cli_test(continue_omega_without_param --rc 2 --match "--omega belongs to --param xI or m0e"
                   -- continue --omega 10 --out c)
impactlab_cli_test(continue_omega_range_with_xI --rc 2 --match "--omega-min belongs to --param omega"
                   -- continue --param xI --omega 10 --min 0 --max 0.01 --omega-min 3 --out c)
impactlab_cli_test(lyapunov_omega_with_sweep --rc 2 --match "--omega is for one omega, not with --sweep"
                   -- lyapunov --omega 16 --sweep up --out l.csv)
impactlab_cli_test(lyapunov_steps_without_sweep --rc 2 --match "--steps goes with '--sweep'" -- lyapunov --omega 16 --steps 5)
impactlab_cli_test(fit_same_file_twice --rc 2 --match "'g.csv' is given twice" --write g.csv "t,x,phi"
                   -- fit g.csv g.csv g.csv --model A1H --report r)
impactlab_cli_test(fit_same_file_two_names --rc 2 --match "'./g.csv' is given twice \\(as 'g.csv'\\)" --write g.csv "t,x,phi"
                   -- fit g.csv ./g.csv --model A1H --report r)

# --- a legal range, a start beyond the bumper -------------------------------------------------------------------
impactlab_cli_test(scan_full_xI_range --rc 0 --csv p.csv "omega,xI,period" 7 7
                   -- scan --model A1G --x omega:10:10:1 --y xI:-0.1:0.1:7 --transient 1 --record 2 --threads 1 --out p.csv)
impactlab_cli_test(simulate_start_beyond_bumper --rc 2 --match "--x0: x = 0.01 m lies beyond the bumper at xI = 0 m"
                   --unchanged s.csv --write s.csv "old" -- simulate --model A1G --x0 0.01 --omega 10 --duration 1 --out s.csv)
impactlab_cli_test(basins_range_beyond_bumper --rc 2 --match "basins: --x-range \\(its upper end\\): x = 0.03 m lies beyond"
                   -- basins --model A1G --omega 13 --grid 4 --x-range -0.03:0.03 --out b.csv)
impactlab_cli_test(orbit_start_beyond_bumper --rc 2 --match "orbit: --from: x = 0.01 m lies beyond the bumper" --absent o.csv
                   -- orbit --model A1G --omega 10 --from 0.01,0 --out o.csv)
impactlab_cli_test(lyapunov_start_beyond_bumper --rc 2 --match "lyapunov: --x0: x = 0.01 m lies beyond the bumper"
                   -- lyapunov --model A1G --omega 16 --x0 0.01)
impactlab_cli_test(simulate_start_in_compliant_bumper --rc 0 --csv s.csv "t,x,v,phi,regime" 10 11
                   -- simulate --model A1C --x0 0.0001 --omega 10 --duration 0.1 --dt 0.01 --out s.csv)

# --- messages ----------------------------------------------------------------------------------------------------
impactlab_cli_test(out_empty_name --rc 2 --match "--out: an empty file name" -- simulate --omega 10 --duration 1 --out=)
impactlab_cli_test(json_duplicate_before_syntax_error --rc 2 --match "d\\.json: key 'xI' appears twice" --no-match "invalid JSON \\(\\)"
                   --write d.json "{\"base\":\"A1C\",\"xI\":0.0,\"xI\":0.002}02}"
                   -- simulate --model d.json --omega 10 --duration 1 --out o.csv)
impactlab_cli_test(json_trailing_garbage --rc 2 --match "t\\.json: line 1, column 15: invalid JSON \\(.*unexpected number"
                   --write t.json "{\"base\":\"A1C\"}02}" -- simulate --model t.json --omega 10 --duration 1 --out o.csv)
impactlab_cli_test(bifurcation_summary_none --rc 0 --match "leaves x~0 none, period 2 none, chaos none" --no-match "nan"
                   -- bifurcation --steps 2 --omega-min 5 --omega-max 6 --transient 1 --record 2 --out d.csv)
# (No brackets or semicolons in these arguments: CMake's lists would split or join them.)
impactlab_cli_test(name_escaped --rc 0 --match "\\\\x1bcred\\\\x0aline: " --csv o.csv "t,x,v,phi,regime" 10 11
                   --write e.json "{\"base\": \"A1H\", \"name\": \"\\u001bcred\\nline\"}"
                   -- simulate --model e.json --omega 10 --duration 0.1 --dt 0.01 --out o.csv)
string(ASCII 27 _esc)
string(ASCII 7 _bel)
impactlab_cli_test(unknown_command_escaped --rc 2 --match "unknown command 'x\\\\x1bc\\\\x07'" -- "x${_esc}c${_bel}")

# --- a full disk: every writing command keeps its old outputs, all of them or none ------------------------------
# fail_writes makes writes fail with ENOSPC after a byte budget (LD_PRELOAD): no root, no tmpfs needed.
add_library(impactlab_fail_writes MODULE ${CMAKE_CURRENT_LIST_DIR}/fail_writes.cpp)
target_link_libraries(impactlab_fail_writes PRIVATE ${CMAKE_DL_LIBS})
add_test(NAME cli.disk_full COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/disk_full.sh $<TARGET_FILE:impactlab>
                                    $<TARGET_FILE:impactlab_fail_writes>)
set_tests_properties(cli.disk_full PROPERTIES LABELS cli TIMEOUT 600)

# --- file names that are not UTF-8: carried as bytes, shown and written escaped -----------------------------------
add_test(NAME cli.names_as_bytes COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/names_as_bytes.sh $<TARGET_FILE:impactlab>)
set_tests_properties(cli.names_as_bytes PROPERTIES LABELS cli TIMEOUT 300)

# --- starts and ranges outside the model's physical range, named with their value ------------------------------
impactlab_cli_test(scan_fold_from_tiny_omega --rc 2 --match "--fold-from': OMEGA = 1e-300 is outside \\[0.05, 1000\\]"
                   -- scan --model A1G --x omega:10:20:3 --y xI:-0.01:0:3 --fold-from 1e-300,-0.0157,0.0023 --png s.png --out s.csv)
impactlab_cli_test(scan_grazing_from_huge --rc 2 --match "--grazing-from': OMEGA = 1e\\+300 is outside"
                   -- scan --model A1G --x omega:10:20:3 --y xI:-0.01:0:3 --grazing-from 1e300,1e300,0 --png s.png --out s.csv)
impactlab_cli_test(scan_fold_from_off_rail --rc 2 --match "--fold-from': X = 0.5 is outside \\[-0.1, 0.1\\] m \\(the rail\\)"
                   -- scan --model A1G --x omega:10:20:3 --y xI:-0.01:0:3 --fold-from 12,0.5,0 --png s.png --out s.csv)
impactlab_cli_test(continue_negative_m0e --rc 2 --match "option '--min': -0.05 is outside \\[0, 10\\]" --absent c
                   -- continue --model A1C --param m0e --omega 10 --min -0.05 --max 0.01 --out c)
impactlab_cli_test(continue_xI_off_rail --rc 2 --match "option '--max': 1.0 is outside \\[-0.1, 0.1\\]" --absent c
                   -- continue --model A1G --param xI --omega 10 --min -0.01 --max 1.0 --out c)
impactlab_cli_test(basins_x_range_off_rail --rc 2 --match "option '--x-range': -0.5 is outside \\[-0.1, 0.1\\]"
                   -- basins --model A1G --omega 13 --grid 4 --x-range -0.5:0 --out b.csv)
impactlab_cli_test(orbit_from_empty_item --rc 2 --match "option '--from': expected X,V \\(two numbers\\), got '0.001,,0'"
                   -- orbit --model A1H --omega 10 --from 0.001,,0 --out o.csv)
impactlab_cli_test(orbit_from_huge_speed --rc 2 --match "option '--from': V = 1e308 is outside \\[-10, 10\\] m/s"
                   -- orbit --model A1H --omega 10 --from 0.001,1e308 --out o.csv)
impactlab_cli_test(orbit_tiny_omega --rc 2 --match "option '--omega': 0.01 is outside \\[0.05, 1000\\]"
                   -- orbit --model A1H --omega 0.01 --out o.csv)
impactlab_cli_test(poincare_subnormal_phi0 --rc 0 --no-match "not a finite number" --csv p.csv "n,x,v" 2 3
                   -- poincare --omega 10 --periods 3 --phi0 1e-320 --out p.csv)
impactlab_cli_test(bifurcation_range_overflow --rc 2 --match "option '--range': '1e309' is not a finite number" --no-match "inf"
                   -- bifurcation --over xI --omega 10 --range 0:1e309 --out d.csv)
impactlab_cli_test(simulate_default_start_beyond_bumper --rc 2
                   --match "the default start x = 0 m lies beyond the bumper at xI = -0.004 m .*: give --x0 X with X <= xI"
                   -- simulate --model A1G --xI -0.004 --omega 10 --duration 1 --out s.csv)

# --- time-dependent effects checked over the run, their clock t0 said ------------------------------------------------
impactlab_cli_test(synth_drift_over_run --rc 2 --match "synth: .*key 'effects.magnet_drift': gives a force of .* \\(at t = [0-9.e+]+ s of the run's 0 .. 1 s\\)"
                   --absent y.csv -- synth --model A1H --effect magnet_drift=1e300 --duration 1 --out y.csv)
impactlab_cli_test(synth_stiffness_drift_over_run --rc 2 --match "synth: .*key 'effects.stiffness_drift': gives a force of"
                   --absent y.csv -- synth --model A1H --effect stiffness_drift=1e10 --duration 1 --out y.csv)
impactlab_cli_test(synth_drift_clock_noted --rc 0 --match "synth: note: effects.magnet_drift.t0 = 1000 s"
                   -- synth --model A1H --effect magnet_drift=-0.0001 --effect magnet_drift.t0=1000 --duration 1 --out y.csv)

# --- sanitizers ---------------------------------------------------------------------------------------------------
# Under AddressSanitizer, LeakSanitizer must not count Open MPI's allocations (mpirun in cli.scan_identity)
# against the project: tests/lsan.supp names the library's frames only. Those libraries have no frame
# pointers, so the fast unwinder would see one frame and no library to match: unwind fully instead.
if(IMPACTLAB_SANITIZE STREQUAL "address" AND TEST cli.scan_identity)
  set_tests_properties(cli.scan_identity PROPERTIES ENVIRONMENT
    "LSAN_OPTIONS=suppressions=${CMAKE_CURRENT_LIST_DIR}/../lsan.supp:print_suppressions=0:fast_unwind_on_malloc=0")
endif()
