"""Run i of a campaign: its scenario (a valid scenario file, docs/simulation.md) and mission_rosfree's options, a pure
function of (spec, i). Every variable is drawn from a stream of its own, seeded by (campaign seed, i, variable name):
adding a key to a spec, or an obstacle drawing more tries, leaves every other variable of every run as it was.

The geometry is what a team would plan (docs/campaign.md): the USV waits at the local origin; the AUV's coverage
area lies `area.distance_m` from it on `area.bearing_deg`; the AUV starts `auv.start_offset_m` from the USV toward
its area; the target lies anywhere in the area; obstacles lie on or near the USV's line from its start to its
station point (`standoff` short of the target), clear of the USV's hull at both ends.
"""
import math
import random

import yaml

STANDOFF_M = 3.0     # the USV holds this far short of the target (mission::UsvMissionParams::standoff)
USV_REACH_M = 5.5    # the USV hull's farthest point from its reference point (sim/contact.h: bow 5.3 m, beam 1.3 m)
PLACEMENT_TRIES = 300


class Draw:
    """Run `index`'s random draws, one stream per name (random.Random seeded by a text: sha512, any platform)."""

    def __init__(self, seed, index):
        self.prefix = "%d/%d/" % (seed, index)

    def stream(self, name):
        return random.Random(self.prefix + name)

    def uniform(self, name, r, rng=None):
        lo, hi = r
        return lo if lo == hi else lo + (hi - lo) * (rng or self.stream(name)).random()

    def integer(self, name, r):
        lo, hi = r
        return min(hi, lo + int((hi - lo + 1) * self.stream(name).random()))

    def choice(self, name, probabilities, rng=None):
        """A key of {name: probability}; the probabilities may sum below 1 (then None is the rest)."""
        u, acc = (rng or self.stream(name)).random(), 0.0
        for k, p in probabilities.items():
            acc += p
            if u < acc:
                return k
        return None if acc < 1.0 - 1e-9 else k


def _r(x, digits=2):
    return round(float(x), digits) + 0.0  # + 0.0: no -0.0 in the files


def _outline_distance(p, ob):
    """Distance from point p (north, east) to an obstacle's outline (0 inside)."""
    d = (p[0] - ob["north"], p[1] - ob["east"])
    if ob["type"] == "buoy":
        return max(0.0, math.hypot(*d) - ob["radius"])
    c, s = math.cos(math.radians(ob["yaw_deg"])), math.sin(math.radians(ob["yaw_deg"]))
    along, across = c * d[0] + s * d[1], -s * d[0] + c * d[1]
    return math.hypot(max(0.0, abs(along) - ob["length"] / 2), max(0.0, abs(across) - ob["width"] / 2))


def _edge_points(ob, step=0.2):
    """Points along a vessel's outline, `step` apart."""
    c, s = math.cos(math.radians(ob["yaw_deg"])), math.sin(math.radians(ob["yaw_deg"]))
    hl, hw = ob["length"] / 2, ob["width"] / 2
    corners = [(hl, hw), (-hl, hw), (-hl, -hw), (hl, -hw), (hl, hw)]
    for (a0, b0), (a1, b1) in zip(corners, corners[1:]):
        n = max(1, int(math.hypot(a1 - a0, b1 - b0) / step))
        for i in range(n):
            a, b = a0 + (a1 - a0) * i / n, b0 + (b1 - b0) * i / n
            yield ob["north"] + c * a - s * b, ob["east"] + s * a + c * b


def _gap(a, b):
    """Distance between two obstacles' outlines (0 when they touch or overlap; to within 0.1 m)."""
    if a["type"] == "buoy":
        return max(0.0, _outline_distance((a["north"], a["east"]), b) - a["radius"])
    if b["type"] == "buoy":
        return _gap(b, a)
    return min(min(_outline_distance(p, b) for p in _edge_points(a)),
               min(_outline_distance(p, a) for p in _edge_points(b)))


def _obstacle_shape(draw, o, rng):
    kind = draw.choice(None, o["type"], rng)
    if kind == "buoy":
        return {"type": "buoy", "radius": _r(draw.uniform(None, o["buoy_radius_m"], rng)),
                "height": _r(draw.uniform(None, o["buoy_height_m"], rng))}
    return {"type": "vessel", "length": _r(draw.uniform(None, o["vessel_length_m"], rng)),
            "width": _r(draw.uniform(None, o["vessel_width_m"], rng)),
            "height": _r(draw.uniform(None, o["vessel_height_m"], rng)),
            "yaw_deg": _r(draw.uniform(None, [0.0, 180.0], rng), 1)}


def obstacles(draw, o, start, station):
    """(placed, dropped): `o.count` obstacles on or near the line start -> station, each clear of the USV's hull at both
    ends and of the others by `o.clearance_m`. One that finds no room in PLACEMENT_TRIES draws (a short transit with
    large vessels) is left out and counted in `dropped`: the run's variables say how many were placed."""
    n = draw.integer("obstacles.count", o["count"])
    line = (station[0] - start[0], station[1] - start[1])
    length = math.hypot(*line)
    normal = (-line[1] / length, line[0] / length)
    clear = USV_REACH_M + o["clearance_m"]
    placed = []
    for k in range(n):
        rng = draw.stream("obstacles[%d]" % k)
        ob = _obstacle_shape(draw, o, rng)
        for _ in range(PLACEMENT_TRIES):
            f, off = draw.uniform(None, o["along"], rng), draw.uniform(None, o["offset_m"], rng)
            ob["north"] = _r(start[0] + f * line[0] + off * normal[0])
            ob["east"] = _r(start[1] + f * line[1] + off * normal[1])
            if (_outline_distance(start, ob) >= clear and _outline_distance(station, ob) >= clear
                    and all(_gap(ob, q) >= o["clearance_m"] for q in placed)):
                placed.append(ob)
                break
    keys = {"buoy": ("type", "north", "east", "radius", "height"),
            "vessel": ("type", "north", "east", "length", "width", "height", "yaw_deg")}
    return [{k: ob[k] for k in keys[ob["type"]]} for ob in placed], n - len(placed)


def _area(draw, a):
    """The coverage rectangle: its nearest point `distance` from the USV (at the origin) on `bearing`."""
    dist, bearing = draw.uniform("area.distance_m", a["distance_m"]), math.radians(draw.uniform("area.bearing_deg",
                                                                                                  a["bearing_deg"]))
    length, width = draw.uniform("area.length_m", a["length_m"]), draw.uniform("area.width_m", a["width_m"])
    # centre at distance + the rectangle's support in that direction: the whole rectangle lies beyond `distance`
    c = dist + abs(math.cos(bearing)) * length / 2 + abs(math.sin(bearing)) * width / 2
    n, e = c * math.cos(bearing), c * math.sin(bearing)
    return {"north_min": _r(n - length / 2), "north_max": _r(n + length / 2), "east_min": _r(e - width / 2),
            "east_max": _r(e + width / 2), "spacing": _r(draw.uniform("area.spacing_m", a["spacing_m"]))}


def _environment(draw, spec, model):
    c, w, wv = spec["current"], spec["wind"], spec["waves"]
    lo, hi = c["speed"]
    speed = draw.uniform("current.speed", [lo, min(hi, c["stem_limit"].get(model, hi))])
    towards = math.radians(draw.uniform("current.direction_deg", c["direction_deg"]))
    wind_speed = draw.uniform("wind.speed", w["speed"])
    env = {
        "current": {"north": _r(speed * math.cos(towards), 3), "east": _r(speed * math.sin(towards), 3),
                    "variation": _r(draw.uniform("current.variation", c["variation"]), 3),
                    "seed": int(draw.stream("current.seed").random() * (2 ** 31 - 1))},  # the sea's seed: an int
        "wind": {"speed": _r(wind_speed),
                 "direction_deg": _r(draw.uniform("wind.direction_deg", w["direction_deg"]), 1),
                 "gust": _r(wind_speed * draw.uniform("wind.gust_factor", w["gust_factor"]))},
        # the wind's sea (fetch-limited growth, docs/simulation.md "Sea state"): its height and period follow from
        # the wind and the open water up-wind of the site, as they would there
        "waves": {"fetch": _r(draw.uniform("waves.fetch_m", wv["fetch_m"]), 0)},
    }
    return env


# The AUV's sonar (sim/sensors.h SonarConfig): 10 m range, a 35-degree vertical fan on a head tilted 15 degrees down.
SONAR_RANGE_M, SONAR_VERTICAL_DEG, SONAR_TILT_DEG = 10.0, 35.0, 15.0
# How far off (horizontally) a pass must see the band's deep end: 7 m, short of the sonar's 10 m, since a target at
# the fan's edge at full range is seen in few sweeps, if at all (envelope seed 1000: from 4.03 m every target deeper
# than 9.2 m was missed although the fan reaches 9.40 m at 10 m).
SURVEY_REACH_M = 7.0


def _fan_angles():
    """The fan's upper and lower edges below the horizontal (the upper one is above it: negative) [rad]."""
    half, tilt = math.radians(SONAR_VERTICAL_DEG / 2), math.radians(SONAR_TILT_DEG)
    return tilt - half, tilt + half


def survey_depths(draw, spec):
    """(depth, second_depth or 0). A number: that depth, one pass. 'plan' (a team knows the band, not where in it the
    target lies): the first pass where the fan at the sonar's full range is centred on the band (0.44 m above to
    5.37 m below the AUV: 2.47 m above the band's middle); when that pass cannot see the band's deep end
    SURVEY_REACH_M off, a second pass from which it can (flown only if the first found nothing)."""
    s = spec["auv"]["survey_depth_m"]
    if s != "plan":
        return draw.uniform("auv.survey_depth_m", s), 0.0
    lo, hi = spec["target"]["depth_m"]
    upper, lower = _fan_angles()
    above, below = -SONAR_RANGE_M * math.sin(upper), SONAR_RANGE_M * math.sin(lower)
    first = max(0.5, (lo + hi) / 2 - (below - above) / 2)
    reach_below = SURVEY_REACH_M * math.tan(lower)
    return first, (hi - reach_below if first + reach_below < hi else 0.0)


def _target(d, spec, area):
    t = spec["target"]
    return {"north": _r(d.uniform("target.north", [area["north_min"], area["north_max"]])),
            "east": _r(d.uniform("target.east", [area["east_min"], area["east_max"]])),
            "depth": _r(d.uniform("target.depth_m", t["depth_m"])), "radius": _r(d.uniform("target.radius_m",
                                                                                          t["radius_m"]))}


def _auv(d, spec, area):
    """Launched `start_offset_m` from the USV toward the centre of its area, facing it."""
    a = spec["auv"]
    bearing = math.atan2((area["east_min"] + area["east_max"]) / 2, (area["north_min"] + area["north_max"]) / 2)
    offset = d.uniform("auv.start_offset_m", a["start_offset_m"])
    return {"start": {"north": _r(offset * math.cos(bearing)), "east": _r(offset * math.sin(bearing)),
                      "depth": _r(d.uniform("auv.start_depth_m", a["start_depth_m"])),
                      "yaw_deg": _r(math.degrees(bearing), 1)},
            "coverage": _coverage(area, *survey_depths(d, spec))}


def _coverage(area, depth, second_depth):
    c = dict(area, depth=_r(depth))
    if second_depth > 0:
        c["second_depth"] = _r(second_depth)
    return c


def generate(spec, index):
    """{scenario, options: {auv_model, seed, faults}, variables} of run `index` (0-based)."""
    d = Draw(spec["seed"], index)
    model = d.choice("auv_model", spec["auv_model"])
    site = spec["site"][d.integer("site", [0, len(spec["site"]) - 1])]
    area = _area(d, spec["area"])
    target = _target(d, spec, area)
    to_target = math.hypot(target["north"], target["east"])
    station = (target["north"] * (1 - STANDOFF_M / to_target), target["east"] * (1 - STANDOFF_M / to_target))
    placed, dropped = obstacles(d, spec["obstacles"], (0.0, 0.0), station)
    fault = d.choice("faults", {i: f["probability"] for i, f in enumerate(spec["faults"])}) if spec["faults"] else None
    fault = spec["faults"][fault]["plan"] if fault is not None else None
    scenario = {
        "name": "%s-%d-%d" % (spec["name"], spec["seed"], index),
        "origin": {k: site[k] for k in ("latitude", "longitude", "altitude")},
        **_environment(d, spec, model),
        "usv": {"start": {"north": 0.0, "east": 0.0, "yaw_deg": _r(d.uniform("usv.yaw_deg", spec["usv"]["yaw_deg"]),
                                                                   1)}},
        "auv": _auv(d, spec, area), "obstacles": placed, "targets": [target],
        "mission": {"expect": "target_reached", **spec["mission"]},
    }
    options = {"auv_model": model, "seed": 1 + int(d.stream("sensor_seed").random() * (10 ** 9 - 1)),
               "faults": fault.split() if fault else []}
    variables = {  # what the report bins success by
        "site": site["name"], "auv_model": model,
        "current_speed_m_s": _r(math.hypot(scenario["current"]["north"], scenario["current"]["east"]), 3),
        "wind_speed_m_s": scenario["wind"]["speed"], "fetch_m": scenario["waves"]["fetch"],
        "obstacles": len(placed), "obstacles_dropped": dropped, "target_depth_m": target["depth"],
        "transit_m": _r(math.hypot(*station), 1), "fault": fault or "none",
    }
    return {"scenario": scenario, "options": options, "variables": variables}


def replay_commands(scenario_file, options, tool="mission_rosfree"):
    """The two commands that replay a run: the ROS-free mission exactly, the ROS main job on the same scenario."""
    faults = "".join(" --fault %s" % f for f in options["faults"])
    return {"rosfree": "%s --scenario %s --auv-model %s --seed %d%s"
                       % (tool, scenario_file, options["auv_model"], options["seed"], faults),
            "ros": "./scripts/mission --scenario %s --auv-model %s%s" % (scenario_file, options["auv_model"], faults)}


def scenario_text(spec, index, run):
    """The scenario file: a comment naming the campaign, the run and how to replay it, then the scenario. The same
    text wherever it is generated (a Dask worker, the client): it names no folder."""
    cmds = replay_commands("THIS_FILE", run["options"])
    head = ("# Campaign '%s' (%s, %s seed %d), run %d, generated by ./scripts/campaign (docs/campaign.md).\n"
            "# Replay exactly (ROS-free): %s\n"
            "# Replay in the ROS main job (its sensor noise: the launch files' seeds): %s\n"
            % (spec["name"], spec.get("file", "spec"), spec["purpose"], spec["seed"], index, cmds["rosfree"],
               cmds["ros"]))
    return head + yaml.safe_dump(run["scenario"], sort_keys=False, default_flow_style=None, width=120)
