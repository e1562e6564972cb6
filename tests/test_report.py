"""The speed-versus-error report runs end to end (short ladders) and says what it measured."""
import json

import pytest

pytest.importorskip("matplotlib")

from benchmarks import report  # noqa: E402


def test_quick_report_writes_tables_plot_and_data(tmp_path):
    assert report.main(["--quick", "--out", str(tmp_path)]) == 0
    text = (tmp_path / "RESULTS.md").read_text()
    data = json.loads((tmp_path / "results.json").read_text())
    assert (tmp_path / "pareto.png").stat().st_size > 10_000
    for scene in ("images", "moving-wall", "seed-adhesive"):
        assert f"## {scene}" in text
    methods = {r["method"] for r in data["rows"]}
    assert set(report.compiled_methods()) | {"baseline"} <= methods
    # every exact-scene row carries a finite error and a positive time
    for r in data["rows"]:
        if r["scene"] != "seed-adhesive":
            assert r["error"] >= 0 and r["time"] > 0
    # cn beats the baseline by a wide margin even on the short ladder
    assert all(v["ratio"] > 5 for v in data["cn_versus_baseline"])
    # the random adhesive scenes: the time distribution and the contract's check, the
    # machine's processor named
    assert "## Random self-affine adhesive scenes" in text
    (row,) = data["random_adhesive"]
    assert row["n"] == 8 and row["median"] > 0 and row["misses"] == 0
    assert data["meta"]["cpu"] and data["meta"]["cpu"] in text
