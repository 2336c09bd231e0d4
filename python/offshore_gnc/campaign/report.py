"""The campaign report (docs/campaign.md, "The report"): success rate with its Wilson 95 % interval, outcome counts,
each figure's distribution (percentiles, histograms), success against each sampled variable (where the envelope
ends), the worst runs with their replay commands. Written to OUT (report.md, report.json, *.png) and printed; the
last printed line is one JSON object."""
import collections
import json
import math
import os

import numpy as np

from offshore_gnc.campaign import generate, runs

# (key in mission_rosfree's JSON, label, the sample count that must be > 0 for the figure to exist, higher is worse)
METRICS = (
    ("usv_xte_true_rmse_m", "USV cross-track RMSE, transit [m]", "usv_xte_est_samples", True),
    ("auv_xte_true_rmse_m", "AUV cross-track RMSE [m]", "auv_xte_true_samples", True),
    ("usv_hold_p95_m", "USV hold at the target, 95th percentile [m]", None, True),
    ("usv_recovery_hold_p95_m", "USV hold in the recovery, 95th percentile [m]", None, True),
    ("usv_wait_drift_m", "USV drift while waiting [m]", None, True),
    ("auv_nav_rmse_m", "AUV navigation error RMSE [m]", None, True),
    ("target_error_m", "target error [m]", None, True),
    ("min_clearance_m", "least clearance, hull to obstacles [m]", None, False),
    ("detection_time_s", "detection time [s]", None, True),
)
# (variable, label, categorical); numeric ones are binned
VARIABLES = (
    ("current_speed_m_s", "current speed [m/s]", False), ("wind_speed_m_s", "wind speed [m/s]", False),
    ("obstacles", "obstacles", True), ("target_depth_m", "target depth [m]", False), ("site", "site", True),
    ("auv_model", "AUV model", True), ("fetch_m", "fetch (waves) [m]", False),
    ("transit_m", "USV transit [m]", False), ("fault", "fault", True),
)
BINS = 5
# The worst first: a skipper's order (a collision is worse than a wrong target is worse than ...).
SEVERITY = ("collision", "wrong_target", "stack_died", "auv_adrift", "off_station", "missed_target", "safety_abort",
            "timeout", "success")
PERCENTILES = (5, 25, 50, 75, 95)


def wilson(k, n, z=1.96):
    """Wilson score interval of a proportion k/n (95 % for z = 1.96): (low, high); (None, None) for n = 0."""
    if n == 0:
        return None, None
    p, d = k / n, 1 + z * z / n
    centre, half = (p + z * z / (2 * n)) / d, z / d * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


# Issue 30 renamed mission_rosfree's cross-track keys (_true: the true position's distance from the leg); a build
# before it printed these (the USV's on its navigation estimate). Delete when no such build is in use.
OLD_NAMES = {"usv_xte_true_rmse_m": "usv_rmse_m", "usv_xte_est_samples": "usv_xte_samples",
             "auv_xte_true_rmse_m": "auv_rmse_m", "auv_xte_true_samples": "auv_xte_samples"}


def figure(record, metric):
    """A run's figure, None when it was not computed: null in the JSON, or computed over no samples (mission_rosfree
    prints 0.0 for a cross-track RMSE of a path never followed)."""
    key, _, samples, _ = metric
    r = record.get("result") or {}
    get = lambda k: r.get(k, r.get(OLD_NAMES.get(k)))  # noqa: E731
    v = get(key)
    return None if v is None or (samples and not get(samples)) else float(v)


def distributions(records):
    out = {}
    for m in METRICS:
        v = np.array([x for x in (figure(r, m) for r in records) if x is not None])
        out[m[0]] = {"n": int(v.size), **({"p%d" % p: round(float(np.percentile(v, p)), 3) for p in PERCENTILES}
                                          if v.size else {}), "max": round(float(v.max()), 3) if v.size else None}
    return out


def _bins(values):
    """BINS equal-width bins over the observed range: [(low, high)]."""
    lo, hi = min(values), max(values)
    if hi - lo < 1e-9:
        return [(lo, hi)]
    edges = np.linspace(lo, hi, BINS + 1)
    return list(zip(edges[:-1], edges[1:]))


def _rate(group):
    k, n = sum(r["outcome"] == "success" for r in group), len(group)
    lo, hi = wilson(k, n)
    return {"n": n, "successes": k, "rate": k / n if n else None, "ci_low": lo, "ci_high": hi}


def success_by(records, variable, categorical):
    """[{bin, n, successes, rate, ci_low, ci_high, by_model: {model: {...}}}] of one sampled variable."""
    values = [r["variables"][variable] for r in records]
    if categorical:
        groups = [(str(c), [r for r in records if r["variables"][variable] == c]) for c in sorted(set(values), key=str)]
    else:
        bins = _bins(values)
        last = len(bins) - 1
        groups = [("%.3g-%.3g" % (a, b), [r for r in records if a <= r["variables"][variable] < b
                                           or (j == last and r["variables"][variable] == b)])
                  for j, (a, b) in enumerate(bins)]
    models = sorted({r["variables"]["auv_model"] for r in records})
    return [dict(bin=name, **_rate(g), by_model={m: _rate([r for r in g if r["variables"]["auv_model"] == m])
                                                 for m in models}) for name, g in groups]


def worst(records, n=10):
    """The n worst runs: by outcome (SEVERITY), then by the worst of their figures' ranks within the campaign."""
    ranks = {}
    for m in METRICS:
        vals = sorted(x for x in (figure(r, m) for r in records) if x is not None)
        for r in records:
            x = figure(r, m)
            if x is not None and len(vals) > 1:
                q = np.searchsorted(vals, x, side="right" if m[3] else "left") / len(vals)
                ranks[r["index"]] = max(ranks.get(r["index"], 0.0), q if m[3] else 1 - q)
    return sorted(records, key=lambda r: (SEVERITY.index(r["outcome"]), -ranks.get(r["index"], 0.0), r["index"]))[:n]


def _plot_metrics(records, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator
    fig, axes = plt.subplots(2, 4, figsize=(18, 8.5))
    for ax, m in zip(axes.flat, METRICS):
        ok = [figure(r, m) for r in records if r["outcome"] == "success"]
        bad = [figure(r, m) for r in records if r["outcome"] != "success"]
        ok, bad = [x for x in ok if x is not None], [x for x in bad if x is not None]
        if ok or bad:
            ax.hist([ok, bad], bins=25, stacked=True, color=["#4c9a2a", "#c0392b"],
                    label=["success (%d)" % len(ok), "failure (%d)" % len(bad)])
            for p, style in ((50, "-"), (95, "--")):
                v = np.percentile(ok + bad, p)
                ax.axvline(v, color="k", ls=style, lw=1.2, label="p%d %.2f" % (p, v))
            ax.legend(fontsize=9)
        ax.set_title(m[1], fontsize=12)
        ax.set_ylabel("runs")
        ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        ax.grid(alpha=0.3)
    fig.suptitle("Figures of %d runs (all outcomes; a figure a run did not reach is left out)" % len(records),
                 fontsize=14)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _plot_success(tables, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(3, 3, figsize=(18, 13))
    markers = {"girona500": ("o", "#1f77b4"), "acolor": ("s", "#ff7f0e")}
    for ax, (var, label, _) in zip(axes.flat, VARIABLES):
        rows = tables[var]
        x = np.arange(len(rows))
        pct = lambda v: np.nan if v is None else 100 * v  # noqa: E731 (an empty bin has no rate)
        rate = np.array([pct(r["rate"]) for r in rows])
        err = np.array([[rate[j] - pct(r["ci_low"]), pct(r["ci_high"]) - rate[j]] for j, r in enumerate(rows)])
        err = np.clip(err.T, 0, None)  # a rate at 100 % may sit a rounding error above its interval's top
        ax.bar(x, rate, color="#9ecae1", yerr=err, capsize=4, label="all (95 % CI)")
        for model, (mk, col) in markers.items():
            pts = [(j, r["by_model"][model]["rate"] * 100) for j, r in enumerate(rows)
                   if model in r["by_model"] and r["by_model"][model]["n"]]
            if pts:
                ax.plot(*zip(*pts), mk, color=col, ms=7, label=model)
        ax.set_xticks(x)
        ax.set_xticklabels(["%s\nn=%d" % (r["bin"], r["n"]) for r in rows], fontsize=8,
                           rotation=30 if len(rows) > 5 else 0)
        ax.set_ylim(0, 105)
        ax.set_title("success rate vs " + label, fontsize=12)
        ax.set_ylabel("success [%]")
        ax.grid(axis="y", alpha=0.3)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=3, fontsize=11)
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    fig.savefig(path, dpi=90)
    plt.close(fig)


def summarise(records, spec, sessions, out):
    """The report as a dict (report.json). Throughput: the runs of every session over their wall time (a resumed
    campaign's too; a session that only wrote the report adds nothing)."""
    n = len(records)
    k = sum(r["outcome"] == "success" for r in records)
    lo, hi = wilson(k, n)
    outcomes = {o: sum(r["outcome"] == o for r in records) for o in runs.OUTCOMES}
    ran, wall = sum(x["ran"] for x in sessions), sum(x["wall_s"] for x in sessions if x["ran"])
    rate, session = (ran / wall if ran and wall else None), sessions[-1]
    return {
        "summary": {
            "campaign": spec["name"], "spec": spec.get("file"), "purpose": spec["purpose"], "seed": spec["seed"],
            "missions": n, "missions_planned": spec["missions"], "successes": k,
            "success_rate": round(k / n, 4) if n else None,
            "success_rate_ci_low": round(lo, 4) if n else None, "success_rate_ci_high": round(hi, 4) if n else None,
            "collisions": outcomes["collision"], "outcomes": outcomes,
            "errors": sum(r["error"] is not None for r in records),
            "missions_per_s": round(rate, 3) if rate else None, "runs_timed": ran, "run_wall_s": round(wall, 1),
            "jobs": session["jobs"], "scheduler": session["scheduler"], "out": out},
        "metrics": distributions(records),
        "success_by": {v: success_by(records, v, cat) for v, _, cat in VARIABLES} if records else {},
        "worst": [r["index"] for r in worst(records)],
        "errors": [{"index": r["index"], "returncode": r["returncode"], "error": r["error"]}
                   for r in records if r["error"] is not None],
    }


def _rate_row(row, models):
    pct = lambda x: "-" if x["rate"] is None else "%.0f %%" % (100 * x["rate"])  # noqa: E731
    ci = "-" if row["rate"] is None else "%.0f-%.0f %%" % (100 * row["ci_low"], 100 * row["ci_high"])
    return "| %s | %d | %s | %s | %s |" % (row["bin"], row["n"], pct(row), ci, " | ".join(
        "%s of %d" % (pct(row["by_model"][m]), row["by_model"][m]["n"]) if row["by_model"].get(m, {}).get("n") else "-"
        for m in models))


def _fmt(v, digits=2):
    return "-" if v is None else ("%.*f" % (digits, v))


def _headline(s):
    t = ["# Campaign '%s' (%s, %s seed %d): %d missions" % (s["campaign"], s["spec"], s["purpose"], s["seed"],
                                                            s["missions"]), ""]
    if s["missions"]:
        t += ["Success: %d of %d = %.1f %% (95 %% Wilson interval %.1f-%.1f %%)" % (
            s["successes"], s["missions"], 100 * s["success_rate"], 100 * s["success_rate_ci_low"],
            100 * s["success_rate_ci_high"]), ""]
    t += ["Outcomes: " + (", ".join("%s %d" % kv for kv in s["outcomes"].items() if kv[1]) or "none"), ""]
    if s["purpose"] == "tuning":
        t += ["(a TUNING campaign: not figures to report; docs/campaign.md)", ""]
    return t


def _figures(report):
    t = ["## Figures (all runs that reached them; p = percentile)", "",
         "| figure | n | p5 | p25 | p50 | p75 | p95 | max |", "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for key, label, _, _ in METRICS:
        d = report["metrics"][key]
        t.append("| %s | %d | %s | %s |" % (label, d["n"], " | ".join(_fmt(d.get("p%d" % p)) for p in PERCENTILES),
                                           _fmt(d["max"])))
    return t + [""]


def _by_variable(report, records):
    t = ["## Success rate by sampled variable (where the envelope ends)", ""]
    models = sorted({r["variables"]["auv_model"] for r in records})
    for var, label, _ in VARIABLES:
        t += ["| %s | runs | success | 95 %% interval | %s |" % (label, " | ".join(models)),
              "| --- " * (4 + len(models)) + "|"]
        t += [_rate_row(r, models) for r in report["success_by"].get(var, [])] + [""]
    return t


def _failures(records):
    why = collections.Counter((r["outcome"], (r["result"] or {}).get("reason") or r["error"].splitlines()[-1])
                              for r in records if r["outcome"] != "success")
    return ["## Failures by reason", ""] + ["- %d x %s: %s" % (k, o, w) for (o, w), k in why.most_common(12)] + [""] \
        if why else []


def _worst(report, records, out, tool):
    by_index = {r["index"]: r for r in records}
    t = ["## The %d worst runs" % len(report["worst"]), ""]
    for i in report["worst"]:
        r, v = by_index[i], by_index[i]["variables"]
        cmds = generate.replay_commands(os.path.join(out, r["scenario"]), r["options"], tool)
        t += ["- run %d: **%s** (%s), %s, %s, current %.2f m/s, wind %.1f m/s, %d obstacles, target %.1f m deep, "
              "fault %s; USV xte %s, AUV xte %s, target error %s, clearance %s" % (
                  i, r["outcome"], (r["result"] or {}).get("reason") or r["error"], v["site"], v["auv_model"],
                  v["current_speed_m_s"], v["wind_speed_m_s"], v["obstacles"], v["target_depth_m"], v["fault"],
                  *(_fmt(figure(r, m)) for m in (METRICS[0], METRICS[1], METRICS[5], METRICS[6]))),
              "  scenario %s" % os.path.join(out, r["scenario"]), "  replay: %s" % cmds["rosfree"],
              "  ROS job: %s" % cmds["ros"]]
    if report["errors"]:
        t += ["", "## Runs that could not run (%d; counted as stack_died)" % len(report["errors"]), ""]
        t += ["- run %d (exit %s): %s" % (e["index"], e["returncode"], e["error"].splitlines()[-1])
              for e in report["errors"][:20]]
    return t + [""]


def _footer(s, out):
    t = ["Report: %s (report.md, report.json, metrics.png, success_by_variable.png; runs/, scenarios/)" % out]
    if s["missions_per_s"]:
        t.append("Throughput: %d runs in %.0f s of wall time, %.2f missions/s (last session: %s)" % (
            s["runs_timed"], s["run_wall_s"], s["missions_per_s"],
            "Dask cluster %s" % s["scheduler"] if s["scheduler"] else "%d local jobs" % s["jobs"]))
    return t


def lines(report, records, out, tool):
    """The report as text lines (printed, and report.md)."""
    s = report["summary"]
    return (_headline(s) + _figures(report) + _by_variable(report, records) + _failures(records)
            + _worst(report, records, out, tool) + _footer(s, out))


def write(out, spec, records, sessions, tool="mission_rosfree", stream=None):
    """Writes OUT/report.{md,json} and the plots, prints the report to `stream` (last line: the summary's JSON);
    returns the summary."""
    report = summarise(records, spec, sessions, out)
    text = lines(report, records, out, tool)
    runs.write_atomic(os.path.join(out, "report.json"), json.dumps(report, indent=1) + "\n")
    runs.write_atomic(os.path.join(out, "report.md"), "\n".join(text + [
        "", "![figures](metrics.png)", "", "![success by variable](success_by_variable.png)"]) + "\n")
    if records:
        _plot_metrics(records, os.path.join(out, "metrics.png"))
        _plot_success(report["success_by"], os.path.join(out, "success_by_variable.png"))
    if stream is not None:
        stream.write("\n".join(text) + "\n" + json.dumps(report["summary"]) + "\n")
        stream.flush()
    return report["summary"]
