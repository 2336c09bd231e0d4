"""The mission report's plots (report.py): map.png, cross_track.png and navigation.png (matplotlib, Agg)."""
import math
import os

from offshore_gnc.report_bags import _stamp, path_ned
from offshore_gnc.report_metrics import OUTLIER_M, SEARCHING


def _plots(out, sc, usv_track, auv_track, u, a, detected, usv_xte, auv_xte, auv_est_track=(), fixes_ok=()):
    """map.png and cross_track.png; usv_xte: (the transit's, the recovery's) [(t, e)]."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon

    after_find = any(m.phase not in SEARCHING for _, m in a["/auv/mission/status"])
    if after_find:  # the recovery is a few metres across: a second panel, 40 m about it
        fig, (ax, zoom) = plt.subplots(1, 2, figsize=(13, 7.5), gridspec_kw={"width_ratios": [1.6, 1]})
    else:
        fig, ax = plt.subplots(figsize=(8, 8))
    # what stands still; a vessel under way (course_deg or track, issue 33) has no one place to draw (not drawn yet)
    for ob in [o for o in sc.get("obstacles", []) or [] if "course_deg" not in o and "track" not in o]:
        ax.add_patch(Circle((ob["east"], ob["north"]), float(ob.get("radius", 0.5)), color="red", alpha=0.6))
    if u["/usv/guidance/safety_boxes"]:
        for box in u["/usv/guidance/safety_boxes"][-1][1].boxes:
            ax.add_patch(Polygon([(c.y, c.x) for c in box.corners], closed=True, fill=False, ec="orange", lw=1.5))
    for vehicle, bag, color in (("usv", u, "green"), ("auv", a, "cyan")):
        # the longest path guidance planned (SBB waypoints included), else the mission's path
        for topic in ("/%s/guidance/planned_path" % vehicle, "/%s/guidance/path" % vehicle):
            paths = [path_ned(m) for _, m in bag[topic]]
            paths = [p for p in paths if p]
            if paths:
                pts = max(paths, key=len)
                ax.plot([p[1] for p in pts], [p[0] for p in pts], "o--", color=color, ms=3, lw=1,
                        label="%s planned path" % vehicle.upper())
                break
    if usv_track:
        ax.plot([p[2] for p in usv_track], [p[1] for p in usv_track], color="blue", lw=2, label="USV trajectory")
    if auv_track:
        ax.plot([p[2] for p in auv_track], [p[1] for p in auv_track], color="purple", lw=1.5, label="AUV trajectory")
    if auv_est_track:
        ax.plot([p[2] for p in auv_est_track], [p[1] for p in auv_est_track], "--", color="magenta", lw=0.8,
                label="AUV estimate (/auv/odom)")
    fix_pts = [(f.position_ned.x, f.position_ned.y) for f in fixes_ok
               if math.isfinite(f.position_ned.x) and math.isfinite(f.position_ned.y)]
    if fix_pts:
        ax.plot([p[1] for p in fix_pts], [p[0] for p in fix_pts], ".", color="darkorange", ms=3, ls="none",
                label="USBL fixes (accepted)")
    for tt in sc.get("targets", []) or []:
        ax.plot(tt["east"], tt["north"], "k*", ms=14, label="target (true)")
    drawn = _draw_recovery(ax, usv_track, auv_track, u["/usv/mission/status"], a["/auv/mission/status"])
    if detected:
        p = detected[1].origin
        ax.plot(p.y, p.x, "rx", ms=12, mew=2, label="target (detected)")
    ax.set_xlabel("east [m]")
    ax.set_ylabel("north [m]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    o = sc.get("origin") or {}
    site = " (about %.5f, %.5f)" % (o["latitude"], o["longitude"]) if "latitude" in o and "longitude" in o else ""
    ax.set_title("Co-operative mission: %s%s" % (sc.get("name", ""), site))
    if after_find:
        for track, color in ((usv_track, "blue"), (auv_track, "purple")):
            if track:
                zoom.plot([p[2] for p in track], [p[1] for p in track], color=color, lw=0.8, alpha=0.5)
        for tt in sc.get("targets", []) or []:
            zoom.plot(tt["east"], tt["north"], "k*", ms=14)
        _draw_recovery(zoom, usv_track, auv_track, u["/usv/mission/status"], a["/auv/mission/status"], legend=False)
        if drawn:
            cn, ce = sum(p[0] for p in drawn) / len(drawn), sum(p[1] for p in drawn) / len(drawn)
            zoom.set_xlim(ce - 20, ce + 20)
            zoom.set_ylim(cn - 20, cn + 20)
        zoom.set_aspect("equal", adjustable="box")
        zoom.grid(True, alpha=0.3)
        zoom.set_xlabel("east [m]")
        zoom.set_title("after the find: hold (square), ascent (orange), surface (circle), recovery (green)", fontsize=8)
    fig.savefig(os.path.join(out, "map.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)

    fig, axs = plt.subplots(2, 1, figsize=(9, 6), sharex=False)
    # time on path: the transit, then the recovery's legs (grey) after it
    usv_transit, usv_recovery = usv_xte
    for axx, xte, rest, name in ((axs[0], usv_transit, usv_recovery, "USV"), (axs[1], auv_xte, [], "AUV")):
        if xte:
            t0 = xte[0][0]
            axx.plot([t - t0 for t, _ in xte], [e for _, e in xte], lw=1, label="transit" if rest else None)
        if rest:
            t0 = rest[0][0] - ((xte[-1][0] - xte[0][0]) if xte else 0.0)
            axx.plot([t - t0 for t, _ in rest], [e for _, e in rest], lw=1, color="0.6",
                     label="the recovery's legs round the AUV (reported apart)")
            axx.legend(loc="lower left", fontsize=8)
        axx.axhline(0, color="k", lw=0.5)
        axx.set_ylabel("%s e(t) [m]" % name)
        axx.grid(True, alpha=0.3)
    axs[1].set_xlabel("time on path [s]")
    fig.suptitle("LOS cross-track error")
    fig.savefig(os.path.join(out, "cross_track.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)


def _draw_recovery(ax, usv_track, auv_track, usv_status, auv_status, legend=True):
    """The recovery on map.png's axes: the AUV's hold point at the find, its ascent (its track while ASCENT), where it
    held at the surface, the USV's way to it (its track from RECOVERY on) and the point it held beside it. Returns the
    points drawn [(north, east)] (empty: nothing after the find)."""
    a = [(_stamp(t, m), m) for t, m in auv_status]
    u = [(_stamp(t, m), m) for t, m in usv_status]
    finite = lambda p: p is not None and p.x == p.x and p.y == p.y  # noqa: E731
    hold = next((m.hold_point for _, m in a if m.phase == "TARGET_FOUND" and finite(m.hold_point)), None)
    surface = next((m.hold_point for _, m in reversed(a) if m.phase in ("SURFACED", "RECOVERED")), None)
    station = next((m.hold_point for _, m in reversed(u) if m.phase in ("RECOVERY", "RECOVERED")), None)
    ascent = [t for t, m in a if m.phase == "ASCENT"]
    recovery = [t for t, m in u if m.phase in ("RECOVERY", "RECOVERED")]
    label = (lambda x: x) if legend else (lambda x: None)
    if ascent:
        pts = [p for p in auv_track if ascent[0] <= p[0] <= ascent[-1] + 0.5]
        ax.plot([p[2] for p in pts], [p[1] for p in pts], color="orange", lw=2.5, label=label("AUV ascent"))
    if recovery and usv_track:
        pts = [p for p in usv_track if p[0] >= recovery[0]]
        ax.plot([p[2] for p in pts], [p[1] for p in pts], color="limegreen", lw=2.5, label=label("USV recovery"))
    drawn = []
    for p, kw, text in ((hold, dict(marker="s", color="blue", mfc="none"), "AUV hold point (at depth)"),
                        (surface, dict(marker="o", color="orange", mfc="none"), "AUV at the surface"),
                        (station, dict(marker="^", color="green"), "USV recovery point")):
        if finite(p):
            ax.plot(p.y, p.x, ls="none", ms=9, mew=2, label=label(text), **kw)
            drawn.append((p.x, p.y))
    if drawn and auv_track:
        ax.plot(auv_track[-1][2], auv_track[-1][1], "x", color="purple", ms=9, mew=2, label=label("AUV at the end"))
    return drawn


def _navigation_plot(out, nav_err, fix_scores, auv_end_t):
    """navigation.png: the AUV's navigation error over time, and each USBL fix's error against the truth by what
    became of it (fused, refused by the filter's gate, rejected by a quality gate), the outlier line drawn."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    if nav_err:
        axs[0].plot([t for t, _ in nav_err], [e for _, e in nav_err], lw=1, color="purple")
    if math.isfinite(auv_end_t):
        for ax in axs:
            ax.axvline(auv_end_t, color="grey", lw=0.8, ls=":")
    axs[0].set_ylabel("navigation error [m]")
    axs[0].grid(True, alpha=0.3)
    floor = 0.02  # fixes without a position (no USV pose near them) are drawn here
    styles = {"fused": ("o", "darkorange", 3, "fused"), "gated": ("x", "red", 6, "refused by the filter's gate"),
              "fit_error": ("+", "blue", 6, "rejected: fit error"), "depth": ("+", "green", 6, "rejected: depth"),
              "stale": ("|", "grey", 6, "rejected: stale (no USV pose in time)")}
    for verdict in sorted({v for _, v, _ in fix_scores}, key=lambda v: (v != "fused", v != "gated", v)):
        pts = [(t, max(e, floor) if e is not None else floor) for t, v, e in fix_scores if v == verdict]
        marker, colour, size, label = styles.get(verdict, ("+", "purple", 6, "rejected: " + verdict))
        axs[1].plot([t for t, _ in pts], [e for _, e in pts], marker, color=colour, ms=size, ls="none",
                    label="%s (%d)" % (label, len(pts)))
    axs[1].axhline(OUTLIER_M, color="k", lw=0.8, ls="--", label="outlier (%.0f m)" % OUTLIER_M)
    axs[1].set_yscale("log")
    axs[1].set_ylim(bottom=floor * 0.7)
    axs[1].set_ylabel("USBL fix error vs truth [m]\n(bottom: no position)")
    axs[1].set_xlabel("simulated time [s] (dotted: the AUV's mission ends)")
    axs[1].grid(True, alpha=0.3)
    axs[1].legend(loc="upper right", fontsize=7)
    fig.suptitle("AUV navigation on USBL fixes")
    fig.savefig(os.path.join(out, "navigation.png"), dpi=110, bbox_inches="tight")
    plt.close(fig)
