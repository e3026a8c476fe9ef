"""The test tiers: which tests leave the test process, and a guard that the others do not.

A test that starts a browser, a ROS 1 graph, a Zenoh session, a process of its own or the
MuJoCo simulator carries the marker of that (``browser``, ``ros1``, ``bus``, ``process``,
``sim``). ``tests/conftest.py`` sets them in ``pytest_collection_modifyitems``: from the
fixtures a test uses (:data:`FIXTURE_TIERS`, looked up over its fixture closure) and, for a
test that starts its process itself, from the folder, module or test it is in
(:data:`PATH_TIERS`). The tests with none of them are the in-process tier (``make test-fast``),
and :func:`in_process_only` holds every one of them to that: starting a process, opening a
Zenoh session or binding a socket to an address other than loopback fails the test, naming
what it did and the marker it needs.
"""

from __future__ import annotations

import contextlib
import ipaddress
import os
import socket
import subprocess
from collections.abc import Callable, Iterable, Iterator
from typing import Any

__all__ = [
    "FIXTURE_TIERS",
    "MARKERS",
    "PATH_TIERS",
    "TierViolation",
    "child_pids",
    "in_process_only",
    "is_loopback_bind",
    "tiers_of",
]

# The markers, as registered with pytest (``pytest --markers`` lists them).
MARKERS: dict[str, str] = {
    "browser": "drives headless Chromium (Debian's chromium package) through playwright",
    "ros1": "runs a ROS 1 graph: a master (ours or Debian's rosmaster) and its nodes",
    "bus": "opens Zenoh sessions: talks to the run's router or to other processes",
    "process": "starts processes (the robomodel CLI, reference tools, routers, launches)",
    "sim": "the simulator's tests (tests/sim): MuJoCo stepped, rendered and driven",
}

# Fixtures that take a test out of the process, by where they are defined (the folder of the
# conftest.py, or the test module) and name: two modules may define fixtures of one name that
# differ (tests/viewer's ``viewer`` starts ``robomodel view``; test_tools_inprocess's does not).
FIXTURE_TIERS: dict[tuple[str, str], tuple[str, ...]] = {
    ("tests", "check_urdf"): ("process",),
    ("tests/viewer", "browser"): ("browser",),
    ("tests/viewer", "page"): ("browser",),
    ("tests/viewer", "viewer"): ("process",),
    ("tests/ros1wire", "ros1"): ("ros1", "process"),
    ("tests/seeds", "ros1_graph"): ("ros1", "process"),
    ("tests/ros1wire/test_hostile_definitions_ros1.py", "evil_graph"): ("ros1", "process"),
    ("tests/ros1wire/test_rosparam_cli.py", "roscore_graph"): ("ros1", "process"),
    ("tests/ros1wire/test_rosparam_cli.py", "graph"): ("ros1", "process"),
    ("tests/seeds", "ros2_ws"): ("process",),
    ("tests/seeds/test_seed_000_planar_3dof.py", "rrbot"): ("ros1", "process"),
    ("tests/seeds/test_seed_000_planar_3dof.py", "rrbot_to_change"): ("ros1", "process"),
    ("tests/seeds/test_seed_000_planar_3dof.py", "display_launch"): ("ros1", "process"),
    ("tests/seeds/test_seed_001_ur5_gazebo.py", "ur5"): ("ros1", "process"),
    ("tests/seeds/test_seed_002_simplebot.py", "simplebot"): ("ros1", "process"),
    ("tests/bag", "talker"): ("process", "bus"),
    ("tests/control/test_cli.py", "rrbot_run"): ("process", "bus"),
    ("tests/launch/test_run_ros2.py", "bus"): ("process", "bus"),
    ("tests/runtime/test_hostile_names.py", "ros1_master"): ("process", "ros1"),
    ("tests/clientlibs/rospy/test_inprocess_master.py", "node"): ("ros1",),
    ("tests/clientlibs/rospy/test_actionlib.py", "node"): ("ros1",),
    ("tests/runtime/test_ros1_connection_caps.py", "endpoint"): ("ros1",),
    ("tests/runtime/test_ros1_master.py", "master"): ("ros1",),
    ("tests/runtime/test_ros1_messages.py", "reference"): ("process",),
    ("tests/runtime/test_subscription_count.py", "master_uri"): ("ros1",),
    ("tests/runtime/test_zenoh_processes.py", "talker"): ("process", "bus"),
    ("tests/runtime/test_zenoh_router.py", "private_router"): ("bus",),
    ("tests/viewer/test_display_qos.py", "zenoh_pair"): ("bus",),
}

PROCESS: tuple[str, ...] = ("process",)
BUS: tuple[str, ...] = ("bus",)
BUS_PROCESS: tuple[str, ...] = ("bus", "process")
ROS1_PROCESS: tuple[str, ...] = ("process", "ros1")

# Tests that leave the process without such a fixture: a folder, a module or one test (its
# nodeid without parameters), with the markers every test under it gets. The guard below finds
# a test missing here (its failure names the marker).
PATH_TIERS: dict[str, tuple[str, ...]] = {
    "tests/netns": ("process", "bus", "ros1"),
    "tests/ros1wire": ROS1_PROCESS,
    "tests/clientlibs/rospy/test_debian_tools.py": ROS1_PROCESS,
    "tests/clientlibs/rospy/test_actionlib_debian.py": ROS1_PROCESS,
    "tests/ros2wire": BUS_PROCESS,
    "tests/seeds": PROCESS,
    "tests/sim/test_teleop_keyboard.py": ("sim", "process", "bus"),
    "tests/sim": ("sim",),
    "tests/bag/test_hostile_bags.py": PROCESS,
    "tests/clientlibs/test_finder_process.py": PROCESS,
    "tests/bridges/test_foxglove_clients.py": BUS_PROCESS,
    "tests/bridges/test_foxglove_same_session.py": BUS,
    "tests/bridges/test_rosbridge_clients.py": BUS_PROCESS,
    "tests/bridges/test_bridges_ros1.py": ROS1_PROCESS,
    "tests/viewer/test_foxglove_beside.py": BUS_PROCESS,
    "tests/bag/test_play.py": PROCESS,
    "tests/runtime/test_large_messages_heap.py": ("bus", "process", "ros1"),
    "tests/runtime/test_zenoh_local_delivery.py": BUS,
    "tests/bag/test_play_modes.py": BUS,
    "tests/bag/test_play_stored_definitions.py": PROCESS,
    "tests/bag/test_record.py": PROCESS,
    "tests/bag/test_record_any_type.py": PROCESS,
    "tests/bag/test_split.py": PROCESS,
    "tests/bag/test_sqlite3.py::test_sqlite3_recording_reads_as_the_mcap_one": PROCESS,
    "tests/clientlibs/rclpy/test_real_rclpy_wins.py": PROCESS,
    "tests/clientlibs/rclpy/test_signals_process.py": PROCESS,
    "tests/clientlibs/rclpy/test_zenoh.py": BUS_PROCESS,
    "tests/control/test_cli.py::test_seed_000_workflow_over_zenoh": PROCESS,
    "tests/control/test_cli.py::test_seed_003_load_with_set_state_start_over_zenoh": PROCESS,
    "tests/description/test_cli.py::test_console_script_runs": PROCESS,
    "tests/description/test_cli.py::test_graph_rendered": PROCESS,
    "tests/description/test_cli.py::test_outputs_get_normal_permissions": PROCESS,
    "tests/description/test_corpus_differential.py::test_graphviz_identical": PROCESS,
    "tests/description/test_corpus_differential.py::test_random_trees_match_check_urdf": PROCESS,
    "tests/description/test_graph_kill.py": PROCESS,
    "tests/description/test_package_discovery.py::test_a_files_own_package_wins_where_the_search_paths_know_none": PROCESS,
    "tests/description/test_package_discovery.py::test_a_package_path_still_wins_over_the_workspace": PROCESS,
    "tests/description/test_package_discovery.py::test_did_you_mean_for_packages_and_frames": PROCESS,
    "tests/description/test_package_discovery.py::test_every_verb_finds_the_inputs_own_package": PROCESS,
    "tests/description/test_package_discovery.py::test_package_not_found_says_where_and_how_in_user_terms": PROCESS,
    "tests/description/test_package_discovery.py::test_sibling_packages_of_the_workspace_are_found": PROCESS,
    "tests/docs/test_docs_commands.py::test_page_commands_run": PROCESS,
    "tests/launch/ros1/test_attribute_values.py::test_attribute_values_match_roslaunch": ROS1_PROCESS,
    "tests/launch/ros1/test_differential.py::test_binfile_param_is_bytes_and_dumps_where_roslaunch_crashes": ROS1_PROCESS,
    "tests/launch/ros1/test_differential.py::test_corpus_matches_roslaunch": ROS1_PROCESS,
    "tests/launch/ros1/test_differential.py::test_examples_match_roslaunch": ROS1_PROCESS,
    "tests/launch/ros1/test_errors.py::test_failing_command": ROS1_PROCESS,
    "tests/launch/ros1/test_state_publishing.py": ROS1_PROCESS,
    "tests/launch/ros2/test_frontends.py::test_temporary_parameter_files_are_removed_at_exit": PROCESS,
    "tests/launch/test_empty_world_hint.py::test_a_ros1_launch_without_spawn_model_gets_the_ros1_line": ROS1_PROCESS,
    "tests/launch/test_empty_world_hint.py::test_seed_003_gazebo_launch_says_that_nothing_was_spawned": PROCESS,
    "tests/launch/test_gazebo_nodes.py::test_shapes_world_launch_runs_the_shapes_world": PROCESS,
    "tests/launch/test_launch_bounds.py::test_a_command_that_hangs_is_stopped_by_the_timeout": PROCESS,
    "tests/launch/test_launch_bounds.py::test_a_command_with_endless_output_is_capped": PROCESS,
    "tests/launch/test_launch_bounds.py::test_non_utf8_rosparam_file_is_an_error_at_its_byte": PROCESS,
    "tests/launch/test_launch_bounds.py::test_ros2_command_substitution_has_the_same_bounds": PROCESS,
    "tests/launch/test_launch_bounds.py::test_ros2_include_fan_out_is_refused": PROCESS,
    "tests/launch/test_launch_bounds.py::test_ros2_launch_refuses_device_files": PROCESS,
    "tests/launch/test_launch_bounds.py::test_roslaunch_include_fan_out_is_refused": PROCESS,
    "tests/launch/test_launch_bounds.py::test_roslaunch_refuses_device_files": PROCESS,
    "tests/launch/test_launch_e2e.py": PROCESS,
    "tests/launch/test_namespaces.py::test_the_viewer_sliders_move_the_robot_of_their_namespace": BUS,
    "tests/launch/test_process_groups.py::test_a_bus_that_hangs_on_close_does_not_keep_the_launch_alive": PROCESS,
    "tests/launch/test_process_groups.py::test_ctrl_c_works_when_started_with_sigint_ignored": PROCESS,
    "tests/launch/test_process_groups.py::test_end_group_ends_background_children_too": PROCESS,
    "tests/launch/test_process_groups.py::test_launch_ends_its_childrens_groups": PROCESS,
    "tests/launch/test_process_groups.py::test_run_bounded_kills_the_tree_on_timeout": PROCESS,
    "tests/launch/test_process_groups.py::test_sigterm_during_a_param_command_ends_the_command_tree": PROCESS,
    "tests/launch/test_process_groups.py::test_the_command_line_exits_past_an_abandoned_session": PROCESS,
    "tests/launch/test_process_groups.py::test_a_viewer_that_hangs_on_close_still_ends_on_ctrl_c": PROCESS,
    "tests/launch/test_ros2_e2e.py": PROCESS,
    "tests/launch/test_run_ros2.py": PROCESS,
    "tests/launch/test_symlink_install.py::test_the_ros2_control_demo_runs_from_a_symlink_install_prefix": PROCESS,
    "tests/launch/test_user_nodes.py": ROS1_PROCESS,
    "tests/clientlibs/test_tf2_ros_ros1_wire.py": ("ros1",),
    "tests/runtime/test_bus_input.py::test_a_bad_attachment_costs_no_other_message": BUS,
    "tests/runtime/test_domain_id.py::test_a_transport_keys_its_graph_by_ros_domain_id": BUS,
    "tests/runtime/test_domain_id.py::test_the_command_line_reads_domain_id_as_rcl": PROCESS,
    "tests/runtime/test_executor_signals.py::test_a_wait_ends_after_a_signal_handler_that_outlasts_it": PROCESS,
    "tests/runtime/test_generated_msgs.py::test_check_names_a_module_that_differs": PROCESS,
    "tests/runtime/test_generated_msgs.py::test_checked_in_modules_are_the_generators_output": PROCESS,
    "tests/runtime/test_graph_flood.py": BUS_PROCESS,
    "tests/runtime/test_hostile_names.py::test_hostile_ros1_names_are_escaped_in_listings": ROS1_PROCESS,
    "tests/runtime/test_hostile_names.py::test_hostile_zenoh_liveliness_names_are_escaped_in_listings": BUS,
    "tests/runtime/test_log_cli.py::test_log_ends_cleanly_on_sigterm": PROCESS,
    "tests/runtime/test_log_cli.py::test_log_shows_matching_nodes_at_or_above_the_level": PROCESS,
    "tests/runtime/test_param_bounds.py::test_an_alias_bomb_in_a_launch_file_is_refused_at_load": PROCESS,
    "tests/runtime/test_param_bounds.py::test_cli_deep_yaml_exits_2_without_traceback": PROCESS,
    "tests/runtime/test_rmw_zenoh_wire.py::test_a_publisher_restarting_with_the_same_gid_loses_none_of_8_messages": BUS,
    "tests/runtime/test_ros1_master_hostile.py::test_peers_that_leave_mid_request_cost_a_line_not_a_traceback": ROS1_PROCESS,
    "tests/runtime/test_ros1_master_hostile.py::test_names_are_bounded_and_validated_and_registrations_bounded": ROS1_PROCESS,
    "tests/runtime/test_ros1_master_hostile.py::test_a_master_answering_garbage_makes_list_exit_2": ROS1_PROCESS,
    "tests/runtime/test_ros1_master_hostile.py::test_a_garbage_subscriber_api_is_refused_and_notifications_go_on": ROS1_PROCESS,
    "tests/runtime/test_ros1_master_hostile.py::test_a_deep_parameter_key_is_refused_and_the_tree_stays_readable": ROS1_PROCESS,
    "tests/runtime/test_ros1_master_hostile.py::test_request_bodies_in_flight_have_one_budget_and_requests_a_cap": ROS1_PROCESS,
    "tests/runtime/test_ros1_messages.py::test_bytes_equal_genpy_both_ways": PROCESS,
    "tests/runtime/test_services.py::test_a_zenoh_call_waits_for_a_server_that_comes_up_late": BUS,
    "tests/runtime/test_services.py::test_a_zenoh_server_that_does_not_answer_in_time_is_said_so": BUS,
    "tests/runtime/test_services.py::test_zenoh_service_across_processes": PROCESS,
    "tests/runtime/test_shipped_interfaces.py::test_ros1_gets_the_shipped_services_ros1_has_with_genmsg_s_md5sums": ROS1_PROCESS,
    "tests/runtime/test_subscription_count.py::test_zenoh_counts_the_graph_s_subscription_tokens": BUS,
    "tests/runtime/test_types_from_actions.py::test_action_feedback_recorded_read_by_rosbags_and_played": PROCESS,
    "tests/runtime/test_types_from_actions.py::test_action_topics_and_services_across_processes": PROCESS,
    "tests/runtime/test_types_from_definitions.py::test_ros1_md5sums_equal_genpy_and_rosbags": PROCESS,
    "tests/runtime/test_types_from_packages.py::test_a_publishers_other_hash_is_named": PROCESS,
    "tests/runtime/test_types_from_packages.py::test_distro_option_of_the_verbs": PROCESS,
    "tests/runtime/test_types_from_packages.py::test_ros1_md5sums_of_package_types_equal_genmsg": ROS1_PROCESS,
    "tests/runtime/test_types_from_packages.py::test_verbs_across_processes": PROCESS,
    "tests/runtime/test_zenoh_clients.py": BUS,
    "tests/runtime/test_zenoh_processes.py": BUS_PROCESS,
    "tests/runtime/test_zenoh_qos.py::test_a_publisher_s_token_carries_its_full_qos": BUS,
    "tests/runtime/test_zenoh_qos.py::test_keep_all_keeps_every_message_and_a_reliable_one_blocks": BUS,
    "tests/runtime/test_zenoh_qos.py::test_a_raw_subscription_on_the_receiving_thread_has_no_queue": BUS,
    "tests/runtime/test_zenoh_router.py::test_a_session_starts_a_router_that_outlives_it": BUS,
    "tests/runtime/test_zenoh_router.py::test_bad_configuration_is_a_clear_error": PROCESS,
    "tests/runtime/test_zenoh_router.py::test_check_attempts_below_zero_skip_the_router": BUS,
    "tests/runtime/test_zenoh_router.py::test_check_attempts_zero_waits_for_a_router": PROCESS,
    "tests/runtime/test_zenoh_router.py::test_domains_do_not_hear_each_other": BUS,
    "tests/runtime/test_zenoh_router.py::test_humble_keys_have_no_type_hash": BUS,
    "tests/runtime/test_zenoh_router.py::test_peers_keep_talking_when_the_router_stops": BUS,
    "tests/runtime/test_zenoh_router.py::test_robomodel_router_serves_peers": PROCESS,
    "tests/runtime/test_zenoh_router.py::test_the_router_ends_when_no_session_uses_it": PROCESS,
    "tests/runtime/test_zenoh_thread_states.py": BUS,
    "tests/test_readme_quickstart.py::test_quickstart_command_runs": PROCESS,
    "tests/runtime/test_rosparam_load.py::test_ns_handling_equals_debian_s_rosparam": PROCESS,
    "tests/docs/test_contributing_mutation.py": PROCESS,
    "tests/description/test_cli.py::test_graph_without_output_writes_what_urdf_to_graphviz_writes": PROCESS,
    "tests/description/test_cli.py::test_new_package_passes_check": PROCESS,
    "tests/description/test_cli.py::test_new_takes_ros2_pkg_create_arguments": PROCESS,
    "tests/description/test_cli.py::test_new_with_dependencies_writes_what_catkin_create_pkg_writes": PROCESS,
    "tests/description/test_cli.py::test_new_rejects_bad_arguments": PROCESS,
    "tests/docs/test_cli_reference.py": PROCESS,
    "tests/test_cli_args.py::test_hostile_run_arguments_are_one_line_and_exit_2": PROCESS,
    "tests/test_system_deps.py": PROCESS,
    "tests/test_tiers.py::test_make_test_fast_s_selection_leaves_the_other_tiers_out": PROCESS,
    "tests/test_wheel_smoke.py": BUS_PROCESS,
    "tests/test_yaml_file_bounds.py::test_robomodel_view_refuses_a_hostile_rviz_file_with_one_line": PROCESS,
    "tests/tf/test_view_frames_names.py::test_dot_runs_with_a_timeout_and_a_size_bound": PROCESS,
    "tests/tf/test_view_frames_names.py::test_graphviz_reads_the_tree_that_was_heard": PROCESS,
    "tests/viewer/test_empty_start.py::test_run_rviz2_without_a_robot_description_serves_an_empty_viewer": PROCESS,
    "tests/viewer/test_view_signals.py": PROCESS,
    "tests/test_import_cycles.py::test_the_script_prints_one_circle_a_line": PROCESS,
    "tests/test_startup_imports.py::test_client_library_finder_loads_only_itself_at_start": PROCESS,
    "tests/test_startup_imports.py::test_a_control_verb_without_a_robot_loads_no_description": PROCESS,
    "tests/test_startup_imports.py::test_check_of_a_urdf_loads_neither_numpy_nor_xacro": PROCESS,
    "tests/test_startup_imports.py::test_check_of_a_xacro_loads_no_numpy": PROCESS,
    "tests/test_startup_imports.py::test_graph_and_new_load_no_numpy": PROCESS,
    "tests/test_startup_imports.py::test_help_imports_no_verb_module": PROCESS,
    "tests/test_startup_imports.py::test_nodes_and_messages_load_no_yaml_until_yaml_is_read_or_written": PROCESS,
    "tests/test_startup_imports.py::test_packages_load_no_sub_package_until_used": PROCESS,
    "tests/test_startup_imports.py::test_version_fast_path_prints_what_argparse_prints": PROCESS,
    "tests/test_startup_imports.py::test_version_loads_only_the_entry_point": PROCESS,
    "tests/test_startup_imports.py::test_xacro_loads_no_urdf_model_and_no_typing": PROCESS,
    "tests/test_user_files.py::test_cli_refuses_dev_zero": PROCESS,
    "tests/test_user_files.py::test_xacro_include_and_load_yaml_of_dev_zero": PROCESS,
    "tests/tf/test_cli.py::test_frames_svg": PROCESS,
    "tests/viewer/test_display_qos.py::test_keep_last_keeps_the_newest_depth_messages_and_keep_all_every_one": BUS,
    "tests/viewer/test_display_qos.py::test_the_zenoh_bus_sees_and_applies_the_display_s_qos": BUS,
    "tests/viewer/test_robot_model_topics.py::test_a_robot_of_another_process_on_the_zenoh_bus": PROCESS,
    "tests/viewer/test_robot_model_topics.py::test_on_ros_1_the_robot_comes_from_the_master_s_parameter": ROS1_PROCESS,
    "tests/viewer/test_rviz_save.py::test_a_launch_whose_rviz_config_does_not_exist_keeps_running": PROCESS,
    "tests/viewer/test_rviz_save.py::test_a_launch_whose_rviz_config_is_malformed_says_where": PROCESS,
    "tests/viewer/test_rviz_save.py::test_a_ros2_launch_s_rviz2_with_a_missing_config_warns_once_and_runs": PROCESS,
    "tests/viewer/test_rviz_save.py::test_the_readme_command_opens_a_missing_config_with_one_warning": PROCESS,
    "tests/viewer/test_units.py::test_importing_the_viewer_loads_neither_viser_nor_trimesh": PROCESS,
    "tests/viewer/test_units.py::test_a_viewer_of_a_robot_without_mesh_files_loads_no_trimesh": PROCESS,
    "tests/viewer/test_viewer_inprocess.py::test_a_description_from_a_topic_is_drawn_with_the_robot_s_tf": PROCESS,
    "tests/xacro/test_examples.py::test_example_passes_check_urdf": PROCESS,
    "tests/xacro/test_work_bound.py::test_cli_refuses_with_exit_2_and_the_stack": PROCESS,
}


# In-process tests that take more than a few seconds (long property-based, corpus and
# real-time tests): marked ``slow``, so that ``make test-fast`` leaves them to ``make test``.
SLOW: tuple[str, ...] = (
    "tests/bridges/test_foxglove_bounds.py::test_a_client_that_stops_reading_costs_bounded_memory",
    "tests/control/test_controllers.py::test_gravity_compensation_holds_the_arm",
    "tests/control/test_controllers.py::test_jtc_effort_pid_mode_moves_rrbot_on_mock_dynamics",
    "tests/control/test_controllers.py::test_rrbot_ros1_pid_over_topics_moves_joint1",
    "tests/control/test_controllers.py::test_seed_000_namespaced_file",
    "tests/control/test_mock_hardware.py::test_effort_integration_swings_a_pendulum_with_the_right_period",
    "tests/control/test_properties.py::test_speed_limiter_bounds_velocity_and_acceleration",
    "tests/control/test_yaml_as_written.py::test_publish_rate_is_honoured_by_elapsed_time",
    "tests/description/test_corpus_differential.py::test_random_round_trip",
    "tests/description/test_corpus_differential.py::test_round_trip",
    "tests/docs/test_docs_commands.py::test_documented_command_parses",
    "tests/docs/test_docs_commands.py::test_documented_options_exist",
    "tests/kinematics/test_backends.py::test_ik_budget_is_iterations_and_results_are_reproducible",
    "tests/kinematics/test_dynamics.py::test_dynamics_matches_pinocchio",
    "tests/kinematics/test_dynamics.py::test_forward_and_inverse_dynamics_round_trip",
    "tests/kinematics/test_fk_pinocchio.py::test_fk_matches_pinocchio",
    "tests/kinematics/test_ik.py::test_ik_batch",
    "tests/kinematics/test_ik.py::test_ik_reaches_random_targets",
    "tests/kinematics/test_ik_options.py::test_one_default_budget_for_ik_and_ik_batch",
    "tests/kinematics/test_readme_example.py::test_the_readme_kinematics_example_runs",
    "tests/kinematics/test_se3.py::test_log_inverts_axis_angle",
    "tests/kinematics/test_ur.py::test_every_solution_reproduces_the_target",
    "tests/launch/test_launch_bounds.py::test_a_doubling_roslaunch_arg_is_refused_at_the_step_that_passes_the_limit",
    "tests/launch/test_launch_bounds.py::test_every_example_launch_file_stays_under_the_work_bound",
    "tests/launch/test_spawner_wait.py::test_a_manager_answering_after_more_than_10_s_gets_its_controllers_spawned",
    "tests/runtime/test_cdr_strings.py::test_a_run_of_messages_matches_pycdr2_message_by_message",
    "tests/runtime/test_definition_build_cost.py::test_building_a_wide_class_compiles_nothing_quadratic",
    "tests/runtime/test_messages.py::test_mixed_alignment_bytes_match_pycdr2",
    "tests/runtime/test_param_bounds.py::test_deep_yaml_is_a_clear_error",
    "tests/runtime/test_ros1_connection_caps.py::test_29_subscriber_connections_past_the_cap_read_an_error_header",
    "tests/runtime/test_ros1_master_hostile.py::test_deep_names_fill_the_server_to_its_limit_in_memory_too",
    "tests/runtime/test_types_from_definitions.py::test_hand_written_equals_generated",
    "tests/runtime/test_types_from_definitions.py::test_round_trip_against_rosbags",
    "tests/test_user_files.py::test_mesh_loaders_refuse_device_files",
    "tests/viewer/test_marker_mesh_tint.py::test_a_textured_part_is_sent_with_its_texels_tinted",
    "tests/viewer/test_rviz_files.py::test_every_tree_reads_back_as_written",
    "tests/viewer/test_rviz_files.py::test_generated_configs_round_trip",
    "tests/viewer/test_tools_inprocess.py::test_steering_publishes_twist_at_10_hz_and_zero_once",
    "tests/viewer/test_units.py::test_meshes_stl_dae_obj_load_and_are_cached",
    "tests/viewer/test_viewer_inprocess.py::test_scene_updates_are_capped_at_the_frame_rate",
    "tests/xacro/test_examples.py::test_synthetic_pr2_size_robot",
    "tests/xacro/test_fuzz.py::test_hostile_documents_raise_only_input_errors",
    "tests/xacro/test_generated.py::test_generated_documents_are_byte_identical",
    "tests/xacro/test_generated.py::test_generated_include_trees_are_byte_identical",
    "tests/xacro/test_units.py::test_eval_literal_matches_reference",
    "tests/xacro/test_units.py::test_lexer_matches_reference_without_nesting",
    "tests/xacro/test_units.py::test_parse_macro_arg_matches_reference",
    "tests/xacro/test_work_bound.py::test_exponential_macro_fan_out_is_refused_by_work",
)
PATH_TIERS.update(dict.fromkeys(SLOW, ("slow",)))


def tiers_of(nodeid: str, fixtures: Iterable[tuple[str, str]]) -> set[str]:
    """The markers of the test ``nodeid`` whose fixture closure is ``fixtures`` (pairs of
    where each is defined, as pytest's ``baseid``, and its name)."""
    found: set[str] = set()
    for fixture in fixtures:
        found.update(FIXTURE_TIERS.get(fixture, ()))
    path, _, test = nodeid.partition("::")
    test = test.split("[", 1)[0]  # a parametrized test's id names its parameters
    for where, markers in PATH_TIERS.items():
        module, _, name = where.partition("::")
        if name:
            hit = path == module and (test == name or test.startswith(name + "::"))
        else:
            hit = path == module or path.startswith(module.rstrip("/") + "/")
        if hit:
            found.update(markers)
    return found


class TierViolation(AssertionError):
    """A test of the in-process tier left the process."""


def is_loopback_bind(family: int, address: Any) -> bool:
    """Whether binding a socket of ``family`` to ``address`` stays on this machine: a Unix
    socket, or an IP socket on a loopback address (``""`` and ``0.0.0.0`` are every address)."""
    if family not in (socket.AF_INET, socket.AF_INET6):
        return True
    host = str(address[0]) if isinstance(address, tuple) and address else ""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.split("%", 1)[0]).is_loopback
    except ValueError:
        return False


def _is_child(pid: str) -> bool:
    """Whether process ``pid``'s parent is this process."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as stat:
            return int(stat.read().rsplit(b")", 1)[1].split()[1]) == os.getpid()
    except (OSError, IndexError, ValueError):
        return False


def child_pids() -> set[int]:
    """The pids of this process's live (not zombie) children, from each of its threads'
    ``/proc/self/task/TID/children``: a few files, where a scan of /proc reads every process's."""
    pids: set[int] = set()
    if os.path.exists(f"/proc/self/task/{os.getpid()}/children"):
        for task in os.scandir("/proc/self/task"):
            with contextlib.suppress(OSError), open(f"{task.path}/children") as listed:
                pids.update(int(pid) for pid in listed.read().split())
    else:  # a kernel without CONFIG_PROC_CHILDREN: every process's parent
        pids = {int(e.name) for e in os.scandir("/proc") if e.name.isdigit() and _is_child(e.name)}
    live: set[int] = set()
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat", "rb") as stat:
                if stat.read().rsplit(b")", 1)[1].split()[0] != b"Z":
                    live.add(pid)
        except (OSError, IndexError):
            continue
    return live


@contextlib.contextmanager
def in_process_only(test: str) -> Iterator[None]:
    """Fail ``test`` (a nodeid, for the message) when, inside the block, it starts a process,
    opens a Zenoh session or binds a socket to an address other than loopback.

    Each such call raises :class:`TierViolation` at once; the block also fails at its end when
    one was made (code under test may have caught the error) or a child process appeared."""
    violations: list[str] = []

    def refuse(what: str, marker: str) -> TierViolation:
        message = (
            f"{test} {what}, but it is in the in-process tier: "
            f"mark it '{marker}' (tests/tiers.py says how)"
        )
        violations.append(message)
        return TierViolation(message)

    def refusing(what: str, marker: str) -> Callable[..., Any]:
        def call(*args: Any, **kwargs: Any) -> Any:
            raise refuse(what, marker)

        return call

    real_bind = socket.socket.bind

    def bind(self: socket.socket, address: Any) -> None:
        if not is_loopback_bind(self.family, address):
            raise refuse(f"binds a socket to {address!r}", "bus")
        real_bind(self, address)

    def execute_child(self: subprocess.Popen[Any], args: Any, *rest: Any, **kw: Any) -> None:
        raise refuse(f"starts a process: {args!r}", "process")

    patches: list[tuple[Any, str, Any]] = [
        (subprocess.Popen, "_execute_child", execute_child),
        (socket.socket, "bind", bind),
    ]
    for name in ("fork", "forkpty", "posix_spawn", "posix_spawnp", "system"):
        if hasattr(os, name):
            patches.append((os, name, refusing(f"starts a process (os.{name})", "process")))
    with contextlib.suppress(ImportError):
        import zenoh

        patches.append((zenoh, "open", refusing("opens a Zenoh session", "bus")))
    saved = [(owner, name, getattr(owner, name)) for owner, name, _ in patches]
    before = child_pids()
    for owner, name, replacement in patches:
        setattr(owner, name, replacement)
    try:
        yield
    finally:
        for owner, name, original in saved:
            setattr(owner, name, original)
    started = child_pids() - before
    if started:
        refuse(f"left child processes {sorted(started)}", "process")
    if violations:
        raise TierViolation("\n".join(dict.fromkeys(violations)))
