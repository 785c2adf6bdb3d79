"""The report: charts exist, and the best-configuration table matches the CSV data."""
import re

from driver.studies import STUDIES
from driver.plots import sphere_cases
from driver.report import LEVELS, write_report


def test_report_charts_and_table_match_the_data(studies, tmp_path):
    # the report of the quick sweep: only its cases, whatever else results/ holds
    quick = {}
    for name, frame in studies.items():
        ids = {c.case_id for c in STUDIES[name](True)}
        quick[name] = frame[frame["case_id"].isin(ids)]
        quick[name].to_csv(tmp_path / f"{name}.csv", index=False)
    studies = quick
    report = write_report(tmp_path)
    text = report.read_text()
    images = re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", text)
    assert len(images) >= 9
    for image in images:
        data = (tmp_path / image).read_bytes()
        assert data.startswith(b"\x89PNG") and len(data) > 20_000, image

    rows = sphere_cases(studies)
    table = [ln for ln in text.splitlines() if ln.startswith("| ") and "%" in ln.split("|")[1]]
    assert len(table) == len(LEVELS)
    for line, level in zip(table, LEVELS):
        cells = [c.strip() for c in line.strip("|").split("|")]
        case_id = cells[-1].strip("`")
        row = rows.set_index("case_id").loc[case_id]
        assert row["max_err"] <= level
        assert float(cells[6]) == round(row["wall_time"], 3)
        assert cells[8] == f"{row['err_p0']:+.4%}" and cells[10] == f"{row['err_a']:+.4%}"
        # nothing faster reaches the same level
        assert rows[rows["max_err"] <= level]["wall_time"].min() == row["wall_time"]
