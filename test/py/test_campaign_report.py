"""The campaign report's arithmetic and the outcome classes (no missions run): the Wilson interval, a run's outcome
class from mission_rosfree's line, figures that were not computed, success by variable, the
worst runs' order."""
import pytest

from offshore_gnc.campaign import report, runs



def test_wilson_interval():
    assert report.wilson(0, 0) == (None, None)
    lo, hi = report.wilson(81, 100)  # textbook value: 0.7222-0.8749
    assert lo == pytest.approx(0.7222, abs=1e-4) and hi == pytest.approx(0.8749, abs=1e-4)
    lo, hi = report.wilson(50, 50)  # all successes: the interval still says how sure
    assert hi == 1.0 and lo == pytest.approx(0.9287, abs=1e-4)
    assert report.wilson(0, 10)[0] == 0.0


@pytest.mark.parametrize("result,rc,expected", [
    ({"success": True, "outcome": "success"}, 0, "success"),
    ({"success": False, "outcome": "collision"}, 1, "collision"),
    ({"success": False, "outcome": "off_station"}, 1, "off_station"),
    (None, 2, "stack_died"),                                        # refused its scenario: never ran
    ({"success": False, "outcome": "timeout"}, -11, "stack_died"),  # crashed
    ({"success": True, "outcome": "USV holds position"}, 0, "stack_died"),  # not a class: not a run to count
])
def test_outcome_class(result, rc, expected):
    assert runs.outcome_class(result, rc) == expected


def record(i, outcome, model="girona500", speed=0.1, **result):
    return {"index": i, "outcome": outcome, "error": None, "variables": {"auv_model": model, "current_speed_m_s": speed},
            "result": result}


def test_figures_not_computed_are_left_out():
    usv, auv = report.METRICS[0], report.METRICS[1]
    assert report.figure(record(0, "success", usv_xte_true_rmse_m=0.7, usv_xte_est_samples=10), usv) == 0.7
    assert report.figure(record(0, "success", usv_xte_true_rmse_m=None, usv_xte_est_samples=10), usv) is None
    # 0.0 over no samples (the target found before the first waypoint) is no figure
    assert report.figure(record(0, "success", auv_xte_true_rmse_m=0.0, auv_xte_true_samples=0), auv) is None
    assert report.figure(record(0, "success", auv_rmse_m=0.4, auv_xte_samples=9), auv) == 0.4  # the old names
    assert report.figure({"index": 0, "result": None}, usv) is None


def test_success_by_bins_and_models():
    recs = [record(i, "success" if i % 4 else "timeout", "acolor" if i % 2 else "girona500", speed=i / 100)
            for i in range(50)]
    rows = report.success_by(recs, "current_speed_m_s", False)
    assert len(rows) == report.BINS and sum(r["n"] for r in rows) == 50  # the top value in the last bin
    assert rows[0]["by_model"]["acolor"]["n"] + rows[0]["by_model"]["girona500"]["n"] == rows[0]["n"]
    models = report.success_by(recs, "auv_model", True)
    assert [r["bin"] for r in models] == ["acolor", "girona500"]
    assert models[0]["rate"] == 1.0  # odd indices: never a multiple of 4


def test_worst_runs_by_outcome_then_figures():
    recs = [record(0, "success", target_error_m=0.1), record(1, "success", target_error_m=1.9),
            record(2, "timeout"), record(3, "collision"), record(4, "missed_target")]
    assert [r["index"] for r in report.worst(recs, 5)] == [3, 4, 2, 1, 0]
