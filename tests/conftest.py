"""Test-session set-up that must happen before numpy is imported.

scipy's Runge-Kutta steps combine the stages with ``numpy.dot``, which OpenBLAS dispatches to a kernel
chosen for the CPU; kernels sum in different orders, so the last bit of a step differs between machines
and a rattling mesh (sensitive to its last bit) can take other steps. The golden check
(``tests/golden``) and the step-for-step engine tests compare integer step counts, so the suite pins
one x86-64 kernel (Haswell: AVX2 + FMA, present on every x86-64 CPU of the last decade) unless the
caller chose one. Subprocesses started by the tests inherit it. The product itself does not pin it.
"""

from __future__ import annotations

import os
import platform


def _x86_with_avx2() -> bool:
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return False
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as f:
            flags = next((line for line in f if line.startswith("flags")), "")
    except OSError:
        return False
    return " avx2" in flags and " fma" in flags


if "OPENBLAS_CORETYPE" not in os.environ and _x86_with_avx2():
    os.environ["OPENBLAS_CORETYPE"] = "Haswell"

# pytest-xdist's workers start with COLUMNS=80 and LINES=24 in their environment (a serial run has neither);
# the tables size themselves by COLUMNS, so a worker would fold lines a serial run does not. Tests that
# need a width set it themselves.
if os.environ.get("PYTEST_XDIST_WORKER"):
    os.environ.pop("COLUMNS", None)
    os.environ.pop("LINES", None)


# The slow tier: tests of more than a few seconds each on the 2-core reference machine (measured with
# --durations), expensive comparisons, the dearer values of parametrisations whose cheaper values stay.
# They run in CI (`.ci/run`: -m "slow or not slow"); the default run (pyproject addopts: -m "not slow")
# leaves them out so that the README's command stays well under two minutes. The extreme catalogue and the
# golden files mark their slow scenes themselves. CONTRIBUTING.md, "Test tiers".
SLOW = (
    # session 24, tr31b: a planetary train and its mirror image simulated (~4 s under load)
    "tests/reference/test_planet_phasing_sense.py::test_the_mirror_image_of_a_planetary_train_carries_the_same_planet_loads",
    # session 23, tr29a: a servo mesh sampled 9.99 times a period, its mean's bound checked (~4 s CPU; the locked
    # 10-a-period run of the same file's other tests stays in the default tier)
    "tests/simulate/test_aliased_stage_names_mean.py::test_a_nearly_locked_stage_s_mean_estimate_bounds_its_miss",
    # session 23, tr29b: a torque drive's periodic run beside a 2 s scipy reference (~9 s under load)
    "tests/reference/test_periodic_torque_drive_period.py",
    # session 23, tr29b: a continued periodic sweep bisecting to a period doubling (~5 s under load)
    "tests/sweep/test_jump_period_doubling.py",
    # session 23, tr28g: a motor-driven report with a transmission error (simulated and settled, ~9 s under load)
    "tests/reference/test_report_motor_mesh_orders.py",
    # session 23, tr28g: a motor-driven fan-load duty point simulated and settled end to end (~8 s under load)
    "tests/life/test_tr28g_motor_k_v.py",
    # session 23, tr28e: a tolerance study's sweep SIGKILLed mid-run, its workers' end awaited, then resumed (~20 s);
    # a sweep with a speed that is no number drawing its plots (~3 s; the Campbell data by hand stays in the test)
    "tests/sweep/test_sweep_campbell_grid.py::test_a_speed_that_is_no_number_fails_its_row_and_the_plots_are_drawn",
    "tests/sweep/test_sweep_parent_killed.py::test_a_killed_sweep_leaves_no_worker_and_its_rerun_finishes_the_set",
    # session 23, tr28f: DOP853 at its stability limit on an undamped chain against an exact linear solution (~3.5 s;
    # its refusal naming a shaft or coupling stays in the default tier)
    "tests/extreme/test_guards.py::test_an_explicit_run_at_its_stability_limit_is_not_warned_of_force_noise_it_does_not_make",
    # session 23, tr28c: a sweep in a fresh process whose numba cannot be imported (~8 s under load; the same refusal
    # with numba missing stays in the default tier, in-process)
    "tests/sweep/test_sweep_compiled_without_numba.py::test_numba_installed_but_not_importable_names_its_error",
    # session 23, tr28d: a torque drive against an overhauling load table, run to its balance twice (~4 s)
    "tests/unit/test_torque_drive_balance.py::test_the_dynamic_factor_refers_to_the_load_where_the_drive_settles_on_an_overhauling_table",
    # session 22, tr27f: a rattling viscous mesh against an independent solve_ivp model with exact contact switching
    # (~4 s; the kink bound's closed-form cases stay in the default tier: tests/unit/test_kink_bound.py)
    "tests/reference/test_viscous_rattle_sampling.py::test_a_rattling_viscous_mesh_s_min_is_estimated_near_its_miss",
    # session 22, tr26a: an idle point's DOL start run end to end and two designs at its class torques (~5 s under
    # load); a motor that cannot drive its point's load, simulated until the refusal (~4 s)
    "tests/life/test_tr26a_idle_starts.py::test_an_idle_points_start_classes_are_rated_at_their_own_load",
    "tests/life/test_tr26a_stalled_point.py::test_a_point_whose_motor_stalls_is_refused_naming_the_stall",
    # session 21, tr24a: torque-driven points on a lossy planetary (reversed, own efficiency) simulated end to end (~6 s;
    # their input torques against the hand balance stay in the default tier)
    "tests/life/test_tr24a_torque_drive_reversed.py::test_the_points_run_at_their_speed",
    "tests/life/test_tr24a_load_table_beyond.py::test_the_point_s_run_carries_the_point_s_torque",  # ~3 s
    # session 20, tr23d: a speed sweep's figures with a plug-in stage (matplotlib and two runs; its Campbell points
    # stay in the default tier: test_the_campbell_points_of_a_train_with_a_plug_in_stage)
    "tests/plugins/test_sweep_plots_plugin.py::test_sweep_plots_of_a_train_with_a_plug_in_stage",
    # round 4, fourteenth session: the README's command read 126 s on the merged suite (4,048 tests); the dearest
    # tests the session's merges brought or slowed, and a few costly duplicates of checks the default tier keeps
    "tests/extreme/test_rattle_span.py::test_a_rattling_window_is_checked_from_the_start",
    "tests/life/test_planet_pin_starts.py::test_the_start_loads_the_pins_with_the_worst_planet_and_k_gamma",  # ~7 s
    "tests/reference/test_planet_errors_start_at_rest.py::test_planet_errors_start_from_the_unloaded_equilibrium",  # ~5 s
    "tests/reference/test_mixer_helical_planetary_hand.py::test_life_starts_in_their_own_classes_and_miner_by_hand",
    "tests/cli/test_plots_mplbackend.py::test_modes_plots_whatever_mplbackend_says[nonsense]",
    "tests/reference/test_trial_tr13.py::test_set_starting_compares_starts_on_a_star_delta_file",
    "tests/reference/test_trial_tr13.py::test_sweep_points_calibrate_the_mesh_at_their_own_load",
    "tests/elements/test_loss_hook.py::test_a_run_with_the_lossy_coupling_closes_its_energy_balance",
    "tests/cli/test_report_trial_rept.py::test_accuracy_study_of_an_unloaded_train_measures_the_mean_force_against",
    "tests/cli/test_report_trial_rep2.py::test_study_reference_within_its_stated_uncertainty_of_an_independent_solve",
    "tests/sweep/test_sweep_stop_mid_result.py::test_stopped_workers_leave_no_pool_thread_waiting_for_the_rest_of",
    "tests/unit/test_spent.py::test_the_kept_check_pass_stays_apart",
    # and the dearer values of parametrisations whose other values stay (a reversed load, a second pole count...)
    "tests/reference/test_planetary_trains_dynamics.py::test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design[ring-sun--2000.0]",
    "tests/reference/test_planetary_trains_dynamics.py::test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design[carrier-sun--2000.0]",
    "tests/reference/test_planetary_trains_dynamics.py::test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design[sun-ring--2000.0]",
    "tests/reference/test_planetary_trains_dynamics.py::test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design[sun-carrier--2000.0]",
    "tests/reference/test_motor_poles_hand.py::test_six_pole_stall_threshold_is_the_locked_rotor_torque[2000.0-True]",
    "tests/reference/test_motor_poles_hand.py::test_a_star_delta_motor_that_falls_back_into_star_is_warned[sets1-True]",
    "tests/reference/test_starts_rigid_engineer.py::test_rigid_peak_is_the_rigid_drivetrains[soft_start_linear]",
    "tests/reference/test_starts_rigid_engineer.py::test_rigid_peak_is_the_rigid_drivetrains[dol_fan]",
    "tests/life/test_starts_engineer.py::test_starts_on_a_drive_that_does_not_start_from_rest_are_warned[sets3-False]",
    "tests/cli/test_cli_broken_pipe.py::test_a_closed_pipe_exits_141_quietly[sweep]",
    "tests/cli/test_cli_hostile_inputs.py::test_a_fifo_without_a_writer_as_input_does_not_hang[sweep]",
    "tests/reference/test_motor_nameplate_hand.py::test_overhauling_load_is_braked_on_the_generating_branch_by_hand[-9000.0-True]",
    # round 4, twelfth session: the dearer values of parametrisations (and one plug-in life run) whose cheaper values
    # stay, measured with --durations on a clean clone (the README's command read 121 s)
    "tests/engine/test_radau.py::test_compiled_jacobian_is_the_generated_one[mixer_time_varying_backlash]",
    "tests/engine/test_radau.py::test_compiled_jacobian_is_the_generated_one[backlash_oscillator]",
    "tests/plugins/test_entry_points.py::test_life_and_the_simulated_rating_use_the_plug_in_standard",
    "tests/life/test_starts_engineer.py::test_starts_on_a_drive_that_does_not_start_from_rest_are_warned[sets1-True]",
    "tests/life/test_starts_engineer.py::test_starts_on_a_drive_that_does_not_start_from_rest_are_warned[sets2-False]",
    "tests/reference/test_radau_contact_steps.py::test_radau_meets_every_single_pair_stretch_of_a_slow_spur_pair[python]",
    "tests/cli/test_sweep_disk_full.py::test_full_disk_mid_sweep[.json]",
    "tests/cli/test_contract_keys_round4.py::test_sweep_rows_with_vary[json]",
    "tests/reference/test_planetary_trains_dynamics.py::test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design[ring-carrier--2000.0]",
    "tests/reference/test_planetary_trains_dynamics.py::test_settled_mean_forces_of_every_arrangement_with_losses_equal_the_design[carrier-ring--2000.0]",
    # round 4, eighth session: the engineers' new hand checks that simulate a whole duty or sweep (7-20 s each on the
    # loaded machine); the cheaper warning checks of the same modules stay in the default tier
    "tests/life/test_starts_engineer.py::test_the_start_damage_from_the_simulated_series_by_hand",
    "tests/life/test_starts_engineer.py::test_the_start_damage_scales_with_the_count_and_none_without_starts",
    "tests/life/test_starts_engineer.py::test_bearings_over_the_duty_and_its_starts_by_hand",
    "tests/life/test_starts_engineer.py::test_a_quiet_window_is_one_class_at_the_static_force",
    "tests/life/test_starts_engineer.py::test_a_periodic_steady_state_counts_a_slow_stages_mesh_cycles",
    "tests/cli/test_sweep_disk_full.py::test_resumed_after_full_disk_equals_uninterrupted",
    "tests/cli/test_cli_fuzz_round4.py::test_a_life_run_shorter_than_the_motor_start_is_lengthened_past_the_start",
    # round 4 (measured with --durations on the merged suite, 2 workers): > ~12 s each
    "tests/engine/test_course.py::test_a_hidden_stiffness_makes_auto_change_course_from_the_state_reached",
    "tests/life/test_starts.py::test_start_record_names_the_bearing_peaks_and_the_bearings_count_the_starts",
    "tests/life/test_starts.py::test_every_point_of_a_dol_duty_comes_from_a_settled_window",
    "tests/life/test_starts.py::test_bearing_static_safety_over_the_duty_takes_the_starts_simulated_peak",
    "tests/life/test_starts.py::test_table_output_shows_the_starts",
    "tests/life/test_starts.py::test_starts_are_classes_of_their_own_and_add_their_own_damage",
    "tests/reference/test_planetary_time_varying.py::test_compiled_engine_matches_python_with_planet_contact_lines",
    "tests/engine/test_radau.py::test_compiled_radau_error_same_order_as_scipy[extreme/stiff_hertz_10000x]",
    "tests/cli/test_cli_report.py::test_plots_four_pngs_from_the_full_report",  # the full report's ladder
    "tests/cli/test_cli_report.py::test_short_ladder_errors_fall_as_the_tolerance_tightens",
    "tests/cli/test_cli_report.py::test_below_resolution_flags_agree_with_the_numbers",
    "tests/engine/test_step_for_step.py::test_same_steps_as_scipy[spur_oscillator_te]",
    "tests/extreme/test_guards.py::test_steps_at_the_cap_run_in_bounded_memory",
    "tests/extreme/test_guards.py::test_the_costliest_measured_combination_finishes_within_its_budget",
    "tests/extreme/test_guards.py::test_a_fast_load_fluctuation_is_not_stopped_by_the_stiffness_budget",
    "tests/cli/test_cli_hostile_audit.py::test_mypy_reports_nothing",  # CI runs mypy itself first
    "tests/engine/test_radau.py::test_compiled_radau_error_same_order_as_scipy[extreme/unequal_inertias]",
    "tests/cli/test_cli_cost_budget.py::test_a_tiny_load_inertia_on_a_stiff_coupling_is_stopped_early_with_the_fix",
    "tests/property/test_bounds_fuzz.py::test_every_numeric_key_at_every_edge_through_design",
    "tests/property/test_bounds_fuzz.py::test_design_and_modes_exit_0_or_2_and_never_print_nan",
    "tests/sweep/test_sweep_continuation.py::test_continuing_keeps_the_ripple_and_the_load_fluctuation_in_phase",
    "tests/unit/test_report_honesty.py::test_reported_error_of_the_default_settings_is_honest",
    "tests/unit/test_report_io.py::test_plots_are_pngs_of_reasonable_size",
    "tests/reference/test_excitation_parametric.py::test_principal_parametric_instability_where_floquet_puts_it",
    "tests/reference/test_excitation_oscillator.py::test_single_and_double_sided_impacts_as_published",
    "tests/reference/test_excitation_oscillator.py::test_coexisting_responses_inside_the_hysteresis_band",
    "tests/cli/test_cli_hostile.py::test_report_in_a_latin_1_terminal_does_not_crash",
    "tests/cli/test_cli_hostile_retest.py::test_report_has_a_run_time_bound",  # runs a report until its budget
    "tests/engine/test_auto_cost.py::test_compiled_radau_stops_a_hopeless_run_as_scipy_does",
    "tests/engine/test_step_for_step.py::test_same_steps_as_scipy[conveyor",  # the conveyor scenes on scipy
    "tests/engine/test_choice.py::test_unsupported_method_requested_compiled_runs_on_python_with_the_reason",
    "tests/cli/test_cli_hostile_retest.py::test_scheduler_address_of_a_web_server_is_a_quick_clear_error[http_server]",
    # round 5 (issue 33 item 5: the README's command within two minutes): the costliest of the default tier
    # (2.5-10 s each on the loaded machine), expensive comparisons (compiled against Python, one route against
    # another) and the dearer values of parametrisations whose cheaper values stay in the default tier
    "tests/reference/test_planetary_train_phasing.py::test_jacobians_with_angles_from_the_planet_kinematics",
    "tests/reference/test_planetary_train_phasing.py::test_compiled_and_python_agree_after_the_planetary_stages",
    "tests/reference/test_planetary_train_phasing.py::test_a_transmission_error_on_the_second_planetary_excites_at_its",
    "tests/reference/test_planetary_train_phasing.py::test_a_transmission_error_after_two_planetary_stages_excites_at_its_own_mesh_frequency[python]",  # [compiled] stays
    "tests/reference/test_planetary_dynamics.py::test_the_compiled_engine_runs_the_planet_meshes_through_the_registry",
    "tests/reference/test_planetary_dynamics.py::test_sequential_phasing_cancels_the_rotational_response",
    "tests/reference/test_planetary_dynamics.py::test_every_held_and_driven_member[sun-ring]",
    "tests/reference/test_planetary_dynamics.py::test_every_held_and_driven_member[ring-sun]",
    "tests/reference/test_planetary_dynamics.py::test_a_planet_with_a_position_error_carries_more_as_the_hand_model_says[2.0]",  # [5.0] stays
    "tests/reference/test_planetary_time_varying.py::test_identical_planets_share_the_mean_load[sequential-25-83]",
    "tests/reference/test_shooting_conveyor.py::test_conveyor_orbit_by_shooting",
    "tests/reference/test_shooting_kahraman_singh.py::test_sweep_up_and_down_through_the_coexistence_band",
    "tests/reference/test_simulate_seed.py::test_stiff_scene_is_integrated_implicitly_and_accurately",
    "tests/cli/test_cli_hostile_retest.py::test_a_signalled_sweep_leaves_no_process_and_no_leaked_semaphore[15-143]",
    "tests/cli/test_cli_hostile_retest.py::test_a_signalled_sweep_leaves_no_process_and_no_leaked_semaphore[1-129]",
    "tests/cli/test_cli_hostile_round4.py::test_sweep_resumed_rows_equal_fresh_rows",
    "tests/cli/test_cli_blas_threads.py::test_a_run_is_the_one_a_dask_worker_computes",  # two subprocess runs
    "tests/cli/test_cli_planetary.py::test_simulate_rates_planetary_stages_at_the_simulated_dynamic_factor",
    "tests/cli/test_cli_planetary.py::test_time_varying_stiffness_on_planet_meshes_runs",
    "tests/sweep/test_sweep_cli.py::test_dask_local_cluster_gives_the_rows_of_the_process_pool",
    "tests/sweep/test_sweep_cli.py::test_plots_response_campbell_and_distributions",
    "tests/sweep/test_sweep_cli.py::test_ctrl_c_then_resume_gives_the_uninterrupted_file[.json]",  # [.csv] stays
    "tests/sweep/test_sweep_compile_once.py::test_a_sweep_compiles_each_model_structure_once",
    "tests/sweep/test_sweep_hysteresis.py::test_jump_up_and_jump_down_happen_at_different_speeds",
    "tests/sweep/test_sweep_bearing_peak_warning.py::test_row_warns_of_the_bearing_overloaded_at_the_window_peak",  # 4.5 s: a sweep and a simulate
    "tests/extreme/test_honesty.py::test_every_statistic_resolved_or_warned[configs/extreme/five_stages.toml]",
    "tests/extreme/test_honesty.py::test_every_statistic_resolved_or_warned[configs/industrial_two_stage.toml]",
    "tests/extreme/test_guards.py::test_forced_methods_that_cannot_resolve_a_very_stiff_mesh_force_are_warned",
    "tests/engine/test_auto_means.py::test_auto_repeats_the_run_at_the_rtol_that_resolves_its_means",
    "tests/engine/test_auto_means.py::test_dop853_at_the_default_rtol_warns_that_its_mean_is_unresolved",
    "tests/engine/test_radau.py::test_compiled_radau_error_same_order_as_scipy[extreme/stiff_linear_10000x]",
    "tests/engine/test_excitation.py::test_compiled_radau_with_transmission_error_is_as_accurate_as_scipys",
    "tests/engine/test_motor_engines.py::test_compiled_run_equals_scipy_on_the_fan_drive",
    "tests/unit/test_settle.py::test_a_window_the_budget_cannot_settle_takes_the_periodic_steady_state",
    "tests/life/test_planetary_dynamic_life.py::test_an_excited_stage_never_reports_less_damage_than_the_static_spectrum",
    "tests/field/test_field_campbell.py::test_sweep_campbell_is_the_same_drawing",
    "tests/field/test_field_ringing.py::test_a_drum_mode_decaying_over_a_window_and_a_half_still_warns",
    "tests/property/test_bounds_fuzz.py::test_simulate_short_runs_exit_0_or_2_and_never_print_nan",
    # a 500,000-entry array parses for seconds; the loader refuses it the same way for every command ([array-design]
    # stays, and every other hostile file still goes through every command)
    "tests/cli/test_cli_hostile_inputs.py::test_hostile_files_through_every_command[array-simulate]",
    "tests/cli/test_cli_hostile_inputs.py::test_hostile_files_through_every_command[array-report]",
    "tests/cli/test_cli_hostile_inputs.py::test_hostile_files_through_every_command[array-modes]",
    "tests/cli/test_cli_hostile_inputs.py::test_hostile_files_through_every_command[array-sweep]",
    "tests/cli/test_cli_hostile_retest.py::test_jobs_are_capped_by_the_machine",  # test_jobs_cap_in_the_session stays
    "tests/cli/test_cli_hostile_retest.py::test_sweep_plots_path_is_escaped_on_stderr",
    "tests/cli/test_cli_hostile_round4.py::test_sweep_resume_with_nothing_to_do_leaves_the_file_byte_identical",
    # a closed stdout or a closed pipe, a fresh interpreter each: the ones that write through the same emit as
    # design (the table and JSON writers) or click's help as --help; design, --help, --version and sweep (rows
    # streamed) stay in the default tier, and simulate for the closed pipe
    "tests/cli/test_cli_hostile_retest.py::test_closed_stdout_is_one_clean_message[design --help]",
    "tests/cli/test_cli_hostile_retest.py::test_closed_stdout_is_one_clean_message[modes ",
    "tests/cli/test_cli_hostile_retest.py::test_closed_stdout_is_one_clean_message[schema]",
    "tests/cli/test_cli_hostile_retest.py::test_closed_stdout_is_one_clean_message[init]",
    "tests/cli/test_cli_hostile_retest.py::test_closed_stdout_is_one_clean_message[simulate ",
    "tests/cli/test_cli_hostile_retest.py::test_closed_stdout_is_one_clean_message[report ",
    "tests/cli/test_cli_broken_pipe.py::test_a_closed_pipe_exits_141_quietly[report]",
    "tests/cli/test_cli_broken_pipe.py::test_a_closed_pipe_exits_141_quietly[design-help]",
    "tests/cli/test_cli_hostile_round4.py::test_a_run_away_motor_is_detected_and_named",
    "tests/field/test_field_ringing.py::test_drum_on_a_soft_coupling_warns_with_what_settles_it",  # conveyor's stays
    "tests/engine/test_radau.py::test_compiled_radau_error_same_order_as_scipy[stiff_linear_mesh]",
    # two `gearcli engine build` processes; a whole compilation (minutes) wherever the cache is not built yet
    "tests/engine/test_engine_build.py::test_a_built_cache_is_reported_with_its_load_time",
    # a whole compilation of the kernel with a test-only element in its dispatch (about a minute)
    "tests/elements/test_loss_hook_compiled.py::test_the_lossy_coupling_runs_compiled_as_it_runs_in_python",
    # round 4, ninth session (the README's command within two minutes: 133 s on a clean clone with these in the
    # default tier): the slowest of --durations, 2-4 s each, each with cheaper siblings of its module kept
    "tests/life/test_trial_duties.py::test_a_conveyor_start_longer_than_the_run_is_counted_whole",
    "tests/engine/test_excitation.py::test_sweep_with_continuation_and_periodic_steady_state_on_the_compiled_engine",
    "tests/unit/test_settle.py::test_run_simulation_moves_an_unsettled_window_of_a_dol_start",
    "tests/sweep/test_sweep_ctrl_c_pool_start.py::test_a_signal_to_the_group_while_the_pool_starts_leaves_no_traceback[2]",
    "tests/cli/test_report_trial_rept.py::test_accuracy_study_names_its_window_when_the_report_run_was_settled_later",
    "tests/cli/test_cli_hostile_retest.py::test_a_signalled_sweep_leaves_no_process_and_no_leaked_semaphore[2-130]",
    "tests/sweep/test_sweep_plot_axes.py::test_roundoff_panels_are_drawn_as_constants_at_their_scale",
    "tests/sweep/test_sweep_resonance.py::test_a_tolerance_study_draws_the_documented_latin_hypercube_and_runs_alike",
    "tests/reference/test_planetary_trains_dynamics.py::test_parallel_then_planetary_then_star_by_hand_and_settled",
    "tests/sweep/test_sweep_resonance.py::test_plots_of_a_speed_sweep_with_a_failed_speed_leave_it_out_and_exit_1",
    "tests/reference/test_motor_poles_hand.py::test_life_counts_the_conveyor_start_n_times_with_the_simulated_peak",
    "tests/reference/test_drivetrain_engineer_checks.py::test_a_slow_helical_mesh_follows_its_contact_line_length",
    "tests/reference/test_dynamics_engineer_scenes.py::test_error_estimate_against_an_independent_solve[1e-08]",
    # round 4, eleventh session (the default tier grew to 3,670 tests with the tenth session's trials): the slowest
    # of --durations on the loaded machine, 3-7 s each, each with cheaper siblings of its module kept
    "tests/life/test_tr10c_starts.py::test_starts_under_a_periodic_steady_state_are_counted_from_rest",
    "tests/life/test_tr10c_starts.py::test_start_span_and_revolutions_match_a_one_shot_run",
    "tests/reference/test_trial_sun_held_sandwich.py::test_simulated_planet_means_against_statics",
    "tests/reference/test_planetary_trains_dynamics.py::test_declared_planet_angles_phase_the_planet_meshes",
    "tests/unit/test_equilibrium.py::test_a_periodic_result_keeps_the_start_of_the_run_it_replaces",
    "tests/reference/test_starts_rigid_engineer.py::test_rigid_peak_is_the_rigid_drivetrains[torque_fan]",  # dol_*,
    "tests/reference/test_starts_rigid_engineer.py::test_rigid_peak_is_the_rigid_drivetrains[star_delta_fan]",  # soft_
    "tests/reference/test_starts_rigid_engineer.py::test_rigid_peak_is_the_rigid_drivetrains[vfd_constant]",  # stay
    "tests/cli/test_cli_hostile_retest.py::test_sighup_is_handled_like_sigterm",  # test_cli_interrupt's SIGTERM stays
    "tests/cli/test_cli_broken_pipe.py::test_a_reader_that_goes_away_mid_output_exits_141",  # the closed pipe stays
    "tests/reference/test_motor_trial_tr10f.py::test_report_on_the_four_pole_fan",
    "tests/cli/test_plots_mplbackend.py::test_modes_plots_whatever_mplbackend_says[TkAgg]",  # [nonsense], [None] stay
    "tests/reference/test_motor_poles_hand.py::test_six_pole_stall_threshold_is_the_locked_rotor_torque[3000.0-False]",
    # session 20 (tr23a): two pool rounds and a worker death, ~5 s; its streaming sibling stays
    "tests/sweep/test_sweep_pool_streams_branch_rows.py::"
    "test_a_branch_whose_worker_dies_after_sending_rows_runs_again_without_sending_them_twice",
    # three simulate runs and a solve_ivp reference, ~7 s; the closed-form tests of the module stay
    "tests/simulate/test_contact_loss_crossings.py::"
    "test_the_spur_oscillator_sampled_40_times_a_mesh_period_reads_its_continuous_loss_fraction",
    # two cold motor starts behind the continued points, ~5 s; the continuation's unit test stays
    "tests/sweep/test_sweep_motor_continuation.py::test_a_continued_motor_point_starts_at_its_own_speed",
    # session 21, tr24f: a soft start rolled back by its load, its rigid start against a hand rigid train solved by
    # solve_ivp and the stiff run (~5 s); the walk's closed-form statics stay (tests/simulate/test_rigid_flow.py)
    "tests/reference/test_rigid_start_losses.py::test_a_rolled_back_start_loses_in_each_mesh_s_own_power_flow",
)


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: costly (tests/conftest.py SLOW); deselected by default, run by CI")
    config.addinivalue_line("markers", "bitwise: exact step counts on the pinned OpenBLAS kernel (slow tier)")


def pytest_collection_modifyitems(config, items):
    import pytest

    for item in items:
        if item.nodeid.startswith(SLOW):
            item.add_marker(pytest.mark.slow)
