"""The ``slow`` marker, applied here to the longest tests (a pytest plugin, loaded by
pyproject's ``addopts``).

The list is kept in one place, measured with ``python -m pytest --durations=25``: every test
that took about 5 s or more on the CI machine. The default run (and CI) runs them all;
``python -m pytest -m "not slow"`` is the quick run for development.
"""

from __future__ import annotations

import pytest

#: ``file::function`` of the slow tests (every parameter of a parametrized test).
SLOW = frozenset({
    "tests/sil/test_sporadic_ramp.py::test_the_controller_steps_it_on_the_minimum_inter_arrival_grid",
    "tests/codegen/test_circuit.py::test_shipped_mission_circuit_agrees",
    "tests/codegen/test_circuit.py::test_random_programs_agree_in_circuit",
    "tests/sil/test_udp_io.py::test_the_udp_controller_drives_the_mujoco_arm",
    "tests/sil/test_supervisor_writes.py::test_the_supervisor_writes_no_parameter_word_in_real_time",
    "tests/campaign/test_budgets.py::test_a_pool_never_has_more_workers_than_runs",
    "tests/campaign/test_budgets.py::test_a_study_database_is_not_a_campaign_database_nor_the_reverse",
    "tests/docs/test_editors_doc.py::test_the_emacs_configuration_shows_diagnostics",
    "tests/sil/test_controller_tree.py::test_an_aarch64_build_under_qemu_ends_as_orccad_run",
    "tests/sil/test_controller_tree.py::test_the_prebuilt_controller_in_real_time_runs_the_same_robot_tasks",
    "tests/sil/test_controller_tree.py::test_the_prebuilt_controller_ends_as_orccad_run",
    "tests/lsp/test_command.py::test_an_editor_that_goes_away_leaves_no_server_and_no_proof_behind",
    "tests/lsp/test_stream.py::test_shutdown_then_exit_is_0_and_the_end_of_the_stream_ends_it_too",
    "tests/fuzz/test_fuzz_lsp.py::test_any_sequence_of_hostile_frames_leaves_the_server_answering",
    "tests/lsp/test_proof.py::test_a_false_property_gets_an_error_with_its_counterexample_script",
    "tests/lsp/test_proof.py::test_every_property_of_arm_recovery_is_proved",
    "tests/reactive/test_reference.py::test_compiled_automaton_agrees_with_the_reference_interpreter",
    "tests/verify/test_spin.py::test_spin_agrees",
    "tests/tui/test_tui_app.py::test_an_arm_run_goes_live_to_its_report_and_exports_its_trace",
    "tests/tui/test_tui_app.py::test_pause_and_speed_keys_drive_the_pacing",
    "tests/tui/test_tui_app.py::test_the_log_filter_keeps_matching_lines",
    "tests/tui/test_tui_app.py::test_a_key_raises_a_declared_input_during_the_run_and_the_mission_recovers",
    "tests/lang/test_parser.py::test_grammar_sentences_parse_or_fail_cleanly",
    "tests/mission/test_mission_run.py::test_type1_exception_retunes_the_running_module",
    "tests/verify/test_counterexample.py::test_check_exits_1_and_its_script_replays_to_the_violation",
    "tests/tui/test_tui_live.py::test_the_trace_is_exported_as_mcap_and_a_bad_suffix_is_refused",
    "tests/verify/symbolic/test_robot_grid.py::test_8x4_is_proved_and_its_false_property_replays_against_the_plant",
})


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        if item.nodeid.split("[", 1)[0] in SLOW:
            item.add_marker(pytest.mark.slow)
