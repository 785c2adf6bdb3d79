#!/usr/bin/env python3
"""Break the guarded code on purpose, one mutation at a time, and check that a test fails.

Each mutation replaces one piece of code and runs the tests that guard it; a
mutation the tests do not catch is a hole in the suite. The files are restored
whatever happens. `make mutate` runs them all (about 10 minutes on 2 cores);
`python tests/mutations.py symbolic --force` runs those whose name holds either word.
"""
from __future__ import annotations

import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


@dataclass
class Mutation:
    name: str
    path: str
    old: str
    new: str
    tests: list[str]


MUTATIONS = [
    # indenter shapes (edp/lib/shape.idp, indenter.idp) and coated bodies
    Mutation("the sphere solved as its parabola", "edp/lib/indenter.idp",
             "x^2*sphereFactor/(sphereRadius + sqrt(max(sphereRadius^2 - x^2, 0.)))",
             "x^2*sphereFactor/(2*sphereRadius)",
             ["tests/test_shapes.py::test_the_exact_sphere_matches_its_exact_solution"]),
    Mutation("a cone's overlap radius off by its cotangent", "edp/lib/shape.idp",
             "  if (shapeKind == CONE) return d/coneCot;", "  if (shapeKind == CONE) return d*coneCot;",
             ["tests/test_shapes.py::test_cones_match_sneddon"]),
    Mutation("16 contact quadrature points per element edge", "edp/lib/fe/quadrature.idp",
             "int subIntervals = ORDER == 1 ? 1 : 3;", "int subIntervals = 8;",
             ["tests/test_physics.py::test_a_stiff_penalty_settles_its_fine_level_in_a_few_steps"]),
    Mutation("P1's gap against the curved indenter", "edp/lib/fe/contact.idp",
             "macro gapSurface() (-depthND + profileNodal) // EOM", "macro gapSurface() indenter // EOM",
             ["tests/test_physics.py::test_a_stiff_p1_penalty_tends_to_the_nodal_exact_solution"]),
    Mutation("P1 contact on 3 sub-intervals per element edge", "edp/lib/fe/quadrature.idp",
             "int subIntervals = ORDER == 1 ? 1 : 3;", "int subIntervals = 3;",
             ["tests/test_physics.py::test_a_stiff_p1_penalty_settles_its_fine_level_in_a_few_steps"]),
    Mutation("the soft-penalty warning reads the P1 chord's sag", "edp/lib/steps/judge.idp",
             "(fixedEdge ? penetrationShiftND : penaltyPenetrationND)*depth",
             "(fixedEdge ? penetrationShiftND : maxPenetrationND)*depth",
             ["tests/test_physics.py::test_a_p1_chord_is_not_called_a_soft_penalty"]),
    Mutation("P1's far field capped like P2's", "edp/lib/fe/section.idp",
             "return order == 1 ? 1.6/n : min(growthCap, 3.2/n);", "return min(growthCap, 3.2/n);",
             ["tests/test_estimate.py::test_the_former_misses_keep_the_promise"]),
    Mutation("the cylinder's a(P) moved by the penetration alone", "edp/lib/steps/estimate.idp",
             "if (isPlane) penaltyCoefficient = [-4., -0.7, 8., 1., -1.];",
             "if (isPlane) penaltyCoefficient = [-4., -0.7, 1., 1., -1.];",
             ["tests/test_estimate.py::test_the_former_misses_keep_the_promise"]),
    Mutation("P1's estimate parts summed with their signs", "edp/lib/steps/estimate.idp",
             " || order == 1;", ";",
             ["tests/test_estimate.py::test_the_former_misses_keep_the_promise"]),
    Mutation("P1's p0 penalty part as P2's", "edp/lib/steps/estimate.idp",
             "if (order == 1) penaltyCoefficient[0] *= 2.5;", "",
             ["tests/test_estimate.py::test_p1_s_penalty_part_is_the_penalty_s_effect"]),
    Mutation("level 0's edge kept however near the axis", "edp/lib/steps/levels.idp",
             "if (!(contactScale > 0.5*overlapX/coarseN)) contactScale = 1;",
             "if (!(contactScale > 0)) contactScale = 1;",
             ["tests/test_shapes.py::test_a_p1_plane_wedge_is_solved_and_says_how_far_off"]),
    Mutation("a fine zone that ends inside its band", "edp/lib/fe/section.idp",
             "real fineRadius = max(1.5*scale, 1.3*bandCenter);", "real fineRadius = 1.5*scale;",
             ["tests/test_shapes.py::test_a_p1_plane_wedge_is_solved_and_says_how_far_off"]),
    Mutation("the mixed form's MUMPS solves left unrefined", "edp/lib/methods/linalg.idp",
             "  if (!mixedForm) return 0;\n  real[int] bFree", "  return 0;\n  real[int] bFree",
             ["tests/test_estimate.py::test_an_incompressible_body_is_solved"]),
    Mutation("4 contact quadrature points per element edge", "edp/lib/fe/quadrature.idp",
             "int subIntervals = ORDER == 1 ? 1 : 3;", "int subIntervals = ORDER == 1 ? 1 : 2;",
             ["tests/test_layers.py::test_a_stiff_penalty_on_a_stiff_film_keeps_its_contact_radius"]),
    Mutation("a fine level solved again left out of coarse_iterations", "edp/lib/steps/levels.idp",
             "    if (index > 2) countLevelBefore();", "",
             ["tests/test_physics.py::test_the_iteration_columns_count_every_level_of_the_history"]),
    Mutation("a soft penalty banded at the exact edge", "edp/lib/steps/levels.idp",
             "  if (coarseSpread) {", "  if (false) {",
             ["tests/test_physics.py::test_a_soft_penalty_bands_its_fine_level_at_its_own_edge"]),
    Mutation("no graded band at a punch's edge", "edp/lib/fe/section.idp",
             "real punchGrading = 3;", "real punchGrading = 1;",
             ["tests/test_shapes.py::test_the_punch_converges_at_its_order_despite_the_edge_singularity"]),
    Mutation("p0 of a cusped tip at the second order", "edp/lib/steps/estimate.idp",
             "  if (k == 0 && profileExponent < 2) return profileExponent - 1;", "",
             ["tests/test_shapes.py::test_power_law_profiles_match_sneddon"]),
    Mutation("an unsorted profile accepted", "edp/lib/shape.idp",
             "    if (!(r[i] > r[i - 1])) bad =", "    if (false) bad =",
             ["tests/test_shapes.py::test_bad_profiles_are_refused_with_the_reason"]),
    Mutation("the substrate's modulus ignored (2D and 3D)", "edp/lib/scene.idp",
             "func muAt = depthBelow < filmDepth ? lameMu : lameMu2;", "func muAt = lameMu;",
             ["tests/test_layers.py::test_intermediate_films_match_the_layered_reference",
              "tests/test_layers.py::test_a_coated_sphere_in_3d_matches_the_layered_reference"]),
    Mutation("the far boundary inside a stiff film's plate", "edp/lib/fe/section.idp",
             "real plateReach = 400;", "real plateReach = 4;",
             ["tests/test_layers.py::test_intermediate_films_match_the_layered_reference"]),
    Mutation("a thin film meshed at the contact's spacing", "edp/lib/fe/section.idp",
             "  real hTop = min(hFine, filmDepth);", "  real hTop = hFine;",
             ["tests/test_layers.py::test_a_thin_layer_on_a_rigid_base",
              "tests/test_layers.py::test_a_thin_compliant_film_is_the_substrate_s_half_space"]),
    Mutation("the layered reference's mismatch coefficient off", "tests/layered_reference.py",
             "    return (m * k2 - k1) / (1 + m * k2), (m - 1) / (m + k1)",
             "    return (m * k2 - k1) / (1 + m * k2), (m - 1) / (m + k2)",
             ["tests/test_layered_reference.py"]),

    # the driver: tables, runs and sweeps
    Mutation("no repair of a line cut by a kill", "driver/table.py",
             'if not raw.endswith(b"\\n"):', "if False:",
             ["tests/test_table.py::test_a_table_is_validated_on_load_and_bad_lines_go_aside_by_number"]),
    Mutation("no kill of running cases on Ctrl-C or a signal", "driver/sweeps.py",
             "        RUNNING.kill_all()\n        raise", "        raise",
             ["tests/test_sweeps.py::test_killing_a_sweep_leaves_no_solver_running_and_resumes"]),
    Mutation("repairs written in place, not atomically", "driver/files.py",
             "        os.replace(tmp, path)", "        path.write_bytes(b''); path.write_bytes(tmp.read_bytes())",
             ["tests/test_table.py::test_a_kill_during_a_table_repair_loses_nothing"]),
    Mutation("bad rows kept", "driver/table.py",
             "        if reason:\n            result.bad.append((number, reason, text))\n            continue",
             "        pass",
             ["tests/test_table.py::test_a_table_is_validated_on_load_and_bad_lines_go_aside_by_number"]),
    Mutation("exit code ignored when a summary exists", "driver/run.py",
             "    if table[status].code != exit_code:", "    if False:",
             ["tests/test_run.py::test_every_solver_fault_is_a_failed_row_with_its_reason"]),
    Mutation("exit codes copied into the driver, not read from -exits", "driver/run.py",
             "    if table[status].code != exit_code:",
             '    if {"converged": 0, "inaccurate": 5}.get(status, 3) != exit_code:',
             ["tests/test_freefem.py::test_the_driver_follows_the_solvers_exit_table"]),
    Mutation("no reaping of a leftover solver on resume", "driver/run.py",
             "    reap_leftover(workdir)\n", "",
             ["tests/test_sweeps.py::test_a_resumed_sweep_kills_a_leftover_solver_of_its_case"]),
    Mutation("comments change the fingerprint", "driver/freefem.py",
             '    return "".join(_COMMENTS.sub("", path.read_text()).split())', "    return path.read_text()",
             ["tests/test_repo.py::test_the_fingerprint_ignores_comments_and_whitespace"]),
    # inputs that lost data, escaped their folder, hung or gave tracebacks
    Mutation("--force deletes the old rows before their reruns land", "driver/sweeps.py",
             '    done = set(frame["case_id"]) - redo\n',
             '    done = set(frame["case_id"]) - redo\n'
             '    if redo:\n'
             '        table.write_atomically(path, frame[~frame["case_id"].isin(redo)].to_csv(index=False))\n',
             ["tests/test_sweeps.py::test_ctrl_c_during_a_forced_rerun_keeps_every_old_row"]),
    Mutation("rows replaced by a rerun are dropped, not kept in stale/", "driver/table.py",
             "    if checked.replaced:", "    if False:",
             ["tests/test_sweeps.py::test_a_completed_forced_rerun_keeps_the_rows_it_replaced_in_stale"]),
    Mutation("a study may be named like the environment record", "driver/layout.py",
             '"bench", Path(ENVIRONMENT_FILE).stem,', '"bench",',
             ["tests/test_sweeps.py::test_study_names_that_would_share_a_projects_file_are_refused"]),
    Mutation("a second run of a case shares the first's folder", "driver/api.py",
             "    for k in range(1, 1000 if unique else 2):", "    for k in range(1, 2):",
             ["tests/test_run.py::test_two_runs_of_one_case_at_once_both_finish"]),
    Mutation("case ids keep path characters", "driver/cases.py",
             '        text = _UNSAFE.sub(lambda m: "".join(f"%{b:02X}" for b in m.group().encode()), text)\n', "",
             ["tests/test_cases.py::test_a_case_id_is_one_safe_file_name_whatever_the_values"]),
    Mutation("word options not checked against their choices", "driver/freefem.py",
             "            if not isinstance(value, str) or value not in (self.choices or []):",
             "            if not isinstance(value, str):",
             ["tests/test_cli.py::test_bad_arguments_are_one_line_and_exit_2"]),
    Mutation("a spec grid is built before it is counted", "driver/sweeps.py",
             "        _check_size(grid.count, yes)", "        _check_size(len(grid.cases()), yes)",
             ["tests/test_studies.py::test_a_grid_is_counted_before_it_is_built"]),
    Mutation("no bounded handshake before the Dask client", "driver/dask_backend.py",
             "                probe(address, timeout)\n", "",
             ["tests/test_cli.py::test_a_scheduler_address_that_speaks_http_fails_within_the_connect_timeout"]),
    Mutation("a chart without rows is drawn anyway", "driver/plots.py",
             '    rows = pd.concat(need(frames, "no study rows"), ignore_index=True)',
             "    rows = pd.concat(frames, ignore_index=True)",
             ["tests/test_report.py::test_one_study_alone_gives_its_charts_and_a_note_for_each_other"]),
    Mutation("a failed write is a traceback", "driver/files.py",
             '        raise error(f"cannot write {path}: {exc.strerror or exc}") from None', "        raise",
             ["tests/test_report.py::test_a_full_disk_is_one_clear_error_and_keeps_the_charts"]),
    Mutation("charts written in place", "driver/plots.py",
             '        files.replace_atomically(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"), ReportError)',
             '        fig.savefig(path, dpi=110, format="png")',
             ["tests/test_report.py::test_an_interrupted_chart_leaves_the_old_one_whole"]),
    Mutation("only the four 2D outputs removed before a run", "driver/run.py",
             "        if path.suffix in OUTPUT_SUFFIXES or path.name in (LOG_FILE, PID_FILE):",
             '        if path.name in ("summary.csv", "profile.csv", "history.csv", "axis.csv", LOG_FILE, PID_FILE):',
             ["tests/test_run.py::test_files_of_an_earlier_run_are_removed_before_a_run"]),
    Mutation("--timeout without an upper bound", "driver/commands/common.py",
             'type=positive(float, MAX_TIMEOUT, "seconds")', "type=positive(float)",
             ["tests/test_cli.py::test_bad_arguments_are_one_line_and_exit_2"]),
    Mutation("a number beyond any float overflows", "driver/freefem.py",
             "        try:\n            return float(number)\n"
             "        except OverflowError:\n            raise wrong from None",
             "        return float(number)",
             ["tests/test_freefem.py::test_bad_values_name_the_option_and_its_range"]),
    Mutation("a Dask connection error is a traceback", "driver/dask_backend.py",
             "        except Exception as exc:  # noqa: BLE001 - "
             "whatever the comm layer raises is one line for the user",
             "        except ZeroDivisionError as exc:",
             ["tests/test_cli.py::test_tls_without_its_settings_is_one_clear_error"]),
    Mutation("a table that is a folder is read as one", "driver/table.py",
             "    if path.exists() and not path.is_file():\n"
             "        raise TableError(f\"the table {path} is not a file\")\n",
             "",
             ["tests/test_table.py::test_a_table_that_is_a_folder_is_one_clear_error"]),
    Mutation("a converged row without its answer counts as done", "driver/table.py",
             "    if status in schema.ANSWERED:", "    if False:",
             ["tests/test_table.py::test_a_hand_edited_answer_without_numbers_is_not_a_finished_case"]),
    Mutation("symbolic links followed", "driver/files.py",
             "    if path.is_symlink():\n        raise error(", "    if False:\n        raise error(",
             ["tests/test_sweeps.py::test_a_planted_link_in_the_results_folder_stops_the_sweep"]),
    Mutation("a repeated JSON key keeps the last value", "driver/studies.py",
             "json.loads(text, object_pairs_hook=_unique_keys)", "json.loads(text)",
             ["tests/test_studies.py::test_a_json_key_given_twice_is_refused"]),
    Mutation("an option given twice keeps the last value", "driver/commands/common.py",
             '            kwargs["action"] = Once', "            pass",
             ["tests/test_cli.py::test_bad_arguments_are_one_line_and_exit_2"]),
    Mutation("importing the driver makes a subreaper", "driver/run.py",
             "RUNNING = Running()\n", "RUNNING = Running()\nbecome_subreaper()\n",
             ["tests/test_run.py::test_importing_the_driver_changes_nothing_in_the_process"]),
    Mutation("adopted orphans never reaped", "driver/run.py",
             '        threading.Thread(target=_reap_forever, name="reaper", daemon=True).start()', "        pass",
             ["tests/test_run.py::test_a_sweep_process_reaps_the_orphans_it_adopts"]),
    Mutation("a rejected run leaves its folder", "driver/api.py",
             "        if rejected(row):\n            # a refused run leaves nothing behind",
             "        if False:\n            # a refused run leaves nothing behind",
             ["tests/test_cli.py::test_a_rejected_run_prints_only_the_error_and_leaves_nothing_behind"]),
    Mutation("a relative work folder handed to the solver as it is", "driver/run.py",
             "    workdir = workdir.absolute()", "    workdir = workdir",
             ["tests/test_run.py::test_a_relative_work_folder_is_the_callers_not_the_solvers"]),
    Mutation("the wheel without the solver scripts", "setup.py",
             "        shutil.copytree(SOURCE, target, ", "        0 and shutil.copytree(SOURCE, target, ",
             ["tests/test_install.py"]),
    Mutation("olive beside green for a status", "driver/plots.py",
             '"inaccurate": "#F0E442"', '"inaccurate": "#c0ca33"',
             ["tests/test_plots.py::test_converged_and_inaccurate_are_far_apart_for_every_reader"]),
    Mutation("the field in units of E again", "driver/fields.py",
             '    mesh[SCALED] = mesh["von_mises"] / p0', '    mesh[SCALED] = mesh["von_mises"]',
             ["tests/test_fields.py::test_the_field_is_drawn_in_units_of_a_and_p0"]),
    Mutation("skips pass unnoticed", "tests/conftest.py",
             '"\\n  ".join(_UNEXPECTED))\n        session.exitstatus = 1', '"\\n  ".join(_UNEXPECTED))\n        pass',
             ["tests/test_repo.py::test_a_skip_without_an_allowed_reason_fails_the_suite"]),
    # the solver (edp/)
    Mutation("output written without the line check", "edp/lib/steps/output.idp",
             'whole = whole && linesIn(outDir + "/" + partName[k] + ".part") == partLines[k];',
             'whole = true;',
             ["tests/test_reliability.py::test_a_failed_write_exits_4_and_keeps_the_earlier_files"]),
    Mutation("the mixed form's indefinite system factorized by Cholesky", "edp/lib/methods/linalg.idp",
             "if (mixedForm) set(Mfactor, solver=sparsesolver);",
             "if (false) set(Mfactor, solver=sparsesolver);",
             ["tests/test_estimate.py::test_an_incompressible_body_is_solved"]),
    Mutation("the 3D semi-axes' estimate parts added with their signs", "edp/lib/steps/estimate.idp",
             "bool uncertain = fixedEdge || (is3d && (k == 2 || k == 3));", "bool uncertain = fixedEdge;",
             ["tests/test_3d.py::test_the_estimate_reads_the_long_semi_axis_along_x_as_along_y"]),
    Mutation("penalties beyond rounding accepted", "edp/lib/steps/levels.idp",
             "if (methodPenaltyForce[methodAsked] && kappa > maxPenaltyND)", "if (false)",
             ["tests/test_reliability.py::test_penalties_rounding_would_fake_are_refused_up_front",
              "tests/test_options.py::test_bad_input_is_one_line_on_stderr_naming_the_option"]),
    Mutation("a far-off answer reported as converged", "edp/lib/steps/judge.idp",
             "if (runStatus == CONVERGED && offByMore) runStatus = INACCURATE;", "",
             ["tests/test_scale_free.py::test_a_far_off_result_is_inaccurate_not_converged"]),
    Mutation("an explicit -tol met at the rounding floor", "edp/lib/methods/newton.idp",
             "      if (!tolGiven && residual < acceptFloor)", "      if (residual < acceptFloor)",
             ["tests/test_reliability.py::test_an_explicit_tolerance_below_the_rounding_floor_is_roundoff_not_converged"]),
    Mutation("the scene's stress unit dropped", "edp/lib/scene.idp",
             "real stressScale = lengthScale > 0 ? Estar*depth/lengthScale : 0;",
             "real stressScale = lengthScale > 0 ? depth/lengthScale : 0;",
             ["tests/test_scale_free.py::test_one_scene_in_three_unit_systems_gives_the_same_run"]),
    Mutation("lagrange releases nodes by the gap only", "edp/lib/methods/lagrange.idp",
             "nodalForce[j] + c*surfaceMass[j]*surfaceGap[j] > 0", "surfaceGap[j] > 0",
             ["tests/test_physics.py::test_lagrange_closes_every_node_to_rounding_for_any_augmentation"]),
    Mutation("no domain term in the estimate", "edp/lib/steps/estimate.idp",
             "estimateDomain[k] = isPlane ? 0 : (farBoundary ? farDomainCoefficient[k]/Lratio^3 : "
             "domainCoefficient[k]/Lratio);",
             "estimateDomain[k] = 0;",
             ["tests/test_reliability.py::test_a_converged_run_far_from_its_estimate_is_inaccurate"]),
    Mutation("missing value absorbed by the next option", "edp/lib/options.idp",
             "      if (!missing) missing = optionIndex(ARGV[i]) >= 0;", "",
             ["tests/test_options.py::test_bad_input_is_one_line_on_stderr_naming_the_option"]),
    Mutation("Uzawa without its stall stop", "edp/lib/methods/uzawa.idp",
             "    if (s - bestUpdate >= 50) return STALLED;", "",
             ["tests/test_reliability.py::test_uzawa_at_a_hopeless_penalty_stops_early"]),
    Mutation("elliptical Hertz with its axes swapped", "edp/lib/reference.idp",
             "hertzEllipseX = Rx >= Ry ? aLong : bShort;", "hertzEllipseX = Rx >= Ry ? bShort : aLong;",
             ["tests/test_3d.py::test_an_ellipsoid_is_solved_in_3d_within_2_percent_of_elliptical_hertz"]),
    Mutation("-model auto solves a sphere in 3D", "edp/lib/scene.idp",
             'else if (Rx == Ry) { model = "axi";', 'else if (Rx == Ry) { model = "3d";',
             ["tests/test_3d.py::test_model_auto_never_models_more_than_the_scene_needs"]),
    Mutation("the far boundary clamped whatever -farfield says", "edp/lib/fe/elasticity2d.idp",
             "  if (farBoundary) farValues = farForm(0, Vh, tgv=1); else farValues = 0;", "  farValues = 0;",
             ["tests/test_load.py::test_the_seed_load_finds_the_seed_depth"]),
    Mutation("the edge fit pinned to the first open node", "edp/lib/steps/measure.idp",
             "hi = pos[min(last + 3, m - 1)];", "hi = pos[last + 1];",
             ["tests/test_3d.py::test_a_stiff_penalty_reads_both_semi_axes_of_an_ellipse"]),
    Mutation("the Tamaas target met by a slower default", "driver/bench.py",
             'line("against Tamaas at equal p0 error", ratio < 1,',
             'line("against Tamaas at equal p0 error", ratio < 2,',
             ["tests/test_bench_targets.py"]),
    Mutation("the depth not settled under -P", "edp/lib/methods/scalars.idp",
             "  if (settlesDepth()) {", "  if (false) {",
             ["tests/test_load.py::test_the_seed_load_finds_the_seed_depth"]),
    Mutation("the stiffness without the far boundary following the force", "edp/lib/methods/scalars.idp",
             "{ return farBoundary ? FD/(1 - FG) : FD; }", "{ return FD; }",
             ["tests/test_load.py::test_the_penalty_stiffness_holds_on_every_mesh"]),
    Mutation("no mixed formulation near incompressibility", "edp/lib/scene.idp",
             '|| (formulation == "auto" && order == 2 && max(nu, nu2) >=', "|| (false && max(nu, nu2) >=",
             ["tests/test_estimate.py::test_nearly_incompressible_bodies_take_the_mixed_formulation"]),
    Mutation("the contact edge from two nodes", "edp/lib/steps/measure.idp",
             "int fitNodes = 6;", "int fitNodes = 2;",
             ["tests/test_physics.py::test_the_fitted_contact_edge_is_within_a_tenth_of_a_percent"]),
    Mutation("no quantization floor under the estimate", "edp/lib/fe/section.idp",
             "real quantizationCoefficient = 1.0;", "real quantizationCoefficient = 0.;",
             ["tests/test_estimate.py::test_a_contact_edge_between_nodes_is_in_the_estimate"]),
    Mutation("extreme radii reach the division by zero", "edp/lib/options.idp",
             "if (Rx < big && Ry < big && max(Rx, Ry) > maxRadiusRatio*min(Rx, Ry))", "if (false)",
             ["tests/test_options.py::test_bad_input_is_one_line_on_stderr_naming_the_option"]),
    Mutation("a fixed point at its rounding floor called diverged", "edp/lib/methods/fixedpoint.idp",
             "bestResidual < 1e-10 ? ROUNDOFF :", "bestResidual < 0 ? ROUNDOFF :",
             ["tests/test_reliability.py::test_a_fixed_point_at_its_rounding_floor_is_roundoff_not_diverged"]),
    Mutation("a .vtu name too long for the file system accepted", "edp/lib/paths.idp",
             "      if (rc != 0 && optionError == \"\")\n        reject(\"-vtk must name a file whose",
             "      if (false)\n        reject(\"-vtk must name a file whose",
             ["tests/test_options.py::test_bad_input_is_one_line_on_stderr_naming_the_option"]),
    Mutation("-model auto tests the radii for equality", "edp/lib/scene.idp",
             "  else if (ellipticityError <= axiBar) {", "  else if (false) {",
             ["tests/test_3d.py::test_model_auto_chooses_by_the_error_of_the_simpler_model"]),
    Mutation("the 3D outline stops at the first open sample", "edp/lib/steps/measure.idp",
             "    if (rayGap(t, s) > -edgeGap) { lo = s; hi = s + reach/samples; }",
             "    if (rayGap(t, s) > -edgeGap && lo < 0) { lo = s; hi = s + reach/samples; }",
             ["tests/test_3d.py::test_the_outline_and_both_profiles_follow_the_hertz_ellipse"]),
]


def run(mutation: Mutation) -> bool:
    """True if a test failed (the mutation is caught)."""
    path = ROOT / mutation.path
    original = path.read_text()
    if original.count(mutation.old) != 1:
        raise SystemExit(f"{mutation.name}: the code to mutate is not found once in {mutation.path}")
    try:
        path.write_text(original.replace(mutation.old, mutation.new))
        proc = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider",
                               *mutation.tests], cwd=ROOT, capture_output=True, text=True)
        return proc.returncode != 0
    finally:
        path.write_text(original)


def main(names: list[str]) -> int:
    """Every mutation, or those whose name contains one of names."""
    chosen = [m for m in MUTATIONS if not names or any(n in m.name for n in names)]
    caught = 0
    for mutation in chosen:
        ok = run(mutation)
        caught += ok
        print(f"{'caught' if ok else 'MISSED'}  {mutation.name}  ({mutation.path})", flush=True)
    print(f"{caught} of {len(chosen)} mutations caught")
    return 0 if caught == len(chosen) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
