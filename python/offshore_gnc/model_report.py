#!/usr/bin/python3
"""Plots and summary of a model_fit report folder (fit.json + series.csv), as thesis Figs. 3.8-3.12.

    python3 -m offshore_gnc.model_report DIR

Writes DIR/track.png (measured vs open-loop simulated track), DIR/<signal>.png for every logged signal
(measured, open-loop run, multiple-shooting segments; the NRMSE fit in the legend) and DIR/report.md.
model_fit runs this itself when given --report.
"""
import json
import math
import os
import sys

LABELS = {
    "u": ("surge speed u", "m/s", "surge"),
    "v": ("sway speed v", "m/s", "sway"),
    "w": ("heave speed w", "m/s", "heave"),
    "r_rad_s": ("yaw rate r", "deg/s", "yaw_rate"),
    "yaw_rad": ("heading", "deg", "heading"),
    "rpm": ("engine speed", "rpm", "rpm"),
    "nozzle": ("nozzle position P", "-", "nozzle"),
    "north": ("north", "m", "north"),
    "east": ("east", "m", "east"),
    "down": ("depth", "m", "depth"),
}
DEGREES = ("r_rad_s", "yaw_rad")


def read_series(path):
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
        cols = {h: [] for h in header}
        for line in f:
            cells = line.rstrip("\n").split(",")
            for h, c in zip(header, cells):
                cols[h].append(float(c) if c else math.nan)
    return cols


def fit_of(report, signal):
    for f in report["fits"]:
        if f["signal"] == signal:
            return f
    return None


def _fmt(v, unit=""):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else ("%.4g%s" % (v, unit))


def plots(out, report, s):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    written = []
    t = s["t"]
    if "north" in s and "east" in s:
        fig, ax = plt.subplots(figsize=(7, 6))
        ax.plot(s["east"], s["north"], "k.", ms=1.5, label="measured")
        fn, fe = fit_of(report, "north"), fit_of(report, "east")
        ax.plot(s["east_open_loop"], s["north_open_loop"], "r-", lw=1,
                label="simulated, open loop (fit N %s %%, E %s %%)" % (
                    _fmt(fn and fn["open_loop_fit_pct"]), _fmt(fe and fe["open_loop_fit_pct"])))
        ax.set_xlabel("east [m]")
        ax.set_ylabel("north [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize=8)
        ax.set_title("%s (%s): track, %s" % (report["vehicle"], report["model"], report["mode"]))
        fig.tight_layout()
        fig.savefig(os.path.join(out, "track.png"), dpi=110)
        plt.close(fig)
        written.append("track.png")
    for sig, (name, unit, fname) in LABELS.items():
        if sig not in s or sig in ("north", "east"):
            continue
        k = 180.0 / math.pi if sig in DEGREES else 1.0
        f = fit_of(report, sig)
        fig, ax = plt.subplots(figsize=(10, 4))
        ax.plot(t, [v * k for v in s[sig]], "k.", ms=1.5, label="measured")
        ax.plot(t, [v * k for v in s[sig + "_open_loop"]], "r-", lw=1,
                label="open loop (fit %s %%)" % _fmt(f and f["open_loop_fit_pct"]))
        if any(not math.isnan(v) for v in s[sig + "_segments"]):
            ax.plot(t, [v * k for v in s[sig + "_segments"]], "b-", lw=0.8, alpha=0.7,
                    label="multiple-shooting segments (fit %s %%)" % _fmt(f and f["segment_fit_pct"]))
        ax.set_xlabel("t [s]")
        ax.set_ylabel("%s [%s]" % (name, unit))
        ax.grid(True, alpha=0.3)
        ax.legend(loc="best", fontsize=8)
        title = "%s: measured vs simulated" % name
        if f and not f.get("motion", True):
            title += " (noise only: no motion to fit)"
        ax.set_title(title)
        fig.tight_layout()
        fig.savefig(os.path.join(out, fname + ".png"), dpi=110)
        plt.close(fig)
        written.append(fname + ".png")
    return written


def summary(out, report, images):
    lines = ["# Model %s: %s (%s)" % ("validation" if report["mode"] == "validate" else "identification",
                                     report["vehicle"], report["model"]), "",
             "Log `%s`, start parameters `%s`: %d rows, %d piece(s), %d segment(s), %d iterations, %.1f s CPU." % (
                 report["input"], report["params"], report["rows"], report["pieces"], report["segments"],
                 report["iterations"], report["cpu_s"]), ""]
    if report["mode"] == "fit":
        lines += ["| parameter | start | fitted | standard error | note |", "| --- | --- | --- | --- | --- |"]
        for p in report["parameters"]:
            if p["estimated"]:
                rel = 100.0 * p["se"] / abs(p["value"]) if p["value"] else math.nan
                lines.append("| %s | %s | %s | %s (%.2g %%) | %s |" % (p["key"], _fmt(p["start"]), _fmt(p["value"]),
                                                                     _fmt(p["se"]), rel, p["note"]))
            else:
                lines.append("| %s | %s | not estimated | | %s |" % (p["key"], _fmt(p["start"]), p["note"]))
        lines.append("")
    lines += ["| signal | samples | residual RMS | segment fit % | open-loop fit % |", "| --- | --- | --- | --- | --- |"]
    for f in report["fits"]:
        lines.append("| %s | %d | %s | %s | %s%s |" % (f["signal"], f["samples"], _fmt(f["residual_rms"]),
                                                     _fmt(f["segment_fit_pct"]), _fmt(f["open_loop_fit_pct"]),
                                                     "" if f.get("motion", True) else " (noise only)"))
    if report["messages"]:
        lines += ["", "Notes:", ""] + ["- " + m for m in report["messages"]]
    lines += [""] + ["![%s](%s)" % (i, i) for i in images]
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print("usage: python3 -m offshore_gnc.model_report DIR", file=sys.stderr)
        return 2
    out = argv[0]
    try:
        with open(os.path.join(out, "fit.json"), encoding="utf-8") as f:
            report = json.load(f)
        series = read_series(os.path.join(out, "series.csv"))
    except (OSError, ValueError) as e:
        print("model_report: %s" % e, file=sys.stderr)
        return 1
    images = plots(out, report, series)
    summary(out, report, images)
    return 0


if __name__ == "__main__":
    sys.exit(main())
