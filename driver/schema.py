"""Column names of the CSV files: the ones hertz.edp writes and the ones the driver adds.

tests/test_driver.py checks SUMMARY_COLUMNS against the header hertz.edp writes.
"""

# summary.csv, as written by hertz.edp (one row per run)
SUMMARY_COLUMNS = [
    "model", "method", "order", "n", "L", "kpen", "omega", "E", "nu", "R", "d",
    "cont", "maxit", "tol", "ndof", "iterations", "factorizations", "resolves", "status", "residual",
    "p0_fe", "p0_hertz", "err_p0", "p0_point", "F_fe", "F_hertz", "err_F",
    "a_fe", "a_hertz", "err_a", "max_penetration", "penetration_over_d",
    "nodal_penetration_over_d",
    "kpen_critical", "t_mesh", "t_assemble", "t_solve", "t_factor", "t_resolve",
    "t_linear_one", "t_total", "accuracy_target", "accuracy_predicted",
    "warnings",
]

# added by the driver to every row of a study CSV
DRIVER_COLUMNS = ["study", "case_id", "edp_hash", "wall_time", "exit_code", "error"]

STUDY_COLUMNS = ["study", "case_id"] + SUMMARY_COLUMNS + DRIVER_COLUMNS[2:]

# statuses: the first three come from hertz.edp, the rest from the driver
STATUSES = ["converged", "diverged", "maxiter", "nan", "timeout", "failed"]
