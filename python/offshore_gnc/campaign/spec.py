"""The campaign spec (config/campaigns/*.yaml, schema in docs/campaign.md): the distributions a campaign draws its
missions from. Validated like a scenario file: an unknown key, a missing one or a value out of range is refused with
a SpecError naming the key (`current.speed`, `faults[1].probability`).

load() returns the spec as a plain dict (JSON-serialisable, shipped sites resolved to their origins), which is all a
run needs: a Dask worker gets that dict, never the file, so its runs cannot depend on what its disk holds.
"""
import hashlib
import json
import numbers
import os

import yaml

from offshore_gnc import vehicles

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
# The sites the repository ships a scenario for (config/scenarios/<name>.yaml; their origins are read from there).
SHIPPED_SITES = ("pyhajarvi", "monterey", "hobart", "stanley", "taveuni", "svalbard")
AUV_MODELS = vehicles.auv_models()
OBSTACLE_TYPES = ("buoy", "vessel")
# Tuning sweeps use seeds below this, reported (evaluation) figures seeds from it on: docs/campaign.md.
EVALUATION_SEED_MIN = 1000


class SpecError(Exception):
    pass


def _fail(key, what):
    raise SpecError("key '%s' %s" % (key, what))


def _number(v, key, lo, hi):
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or v != v:
        _fail(key, "must be a number, not %r" % (v,))
    if not lo <= v <= hi:
        _fail(key, "= %g is out of range [%g, %g]" % (v, lo, hi))
    return float(v)


# ---------------------------------------------------------------- leaf checkers: (value, key) -> normalised value
def dist(lo, hi, default=None):
    """A number (constant) or [low, high] (uniform); normalised to [low, high]."""
    def check(v, key):
        if isinstance(v, list):
            if len(v) != 2:
                _fail(key, "must be a number or [low, high]")
            a, b = _number(v[0], key + "[0]", lo, hi), _number(v[1], key + "[1]", lo, hi)
            if a > b:
                _fail(key, "= [%g, %g]: low above high" % (a, b))
            return [a, b]
        x = _number(v, key, lo, hi)
        return [x, x]
    check.default = None if default is None else [default, default] if not isinstance(default, list) else default
    return check


def count(lo, hi, default=None):
    """An integer or [low, high] (each integer equally likely)."""
    inner = dist(lo, hi, default)

    def check(v, key):
        r = inner(v, key)
        if any(x != int(x) for x in r):
            _fail(key, "must be whole numbers")
        return [int(x) for x in r]
    check.default = inner.default
    return check


def number(lo, hi, default=None):
    def check(v, key):
        return _number(v, key, lo, hi)
    check.default = default
    return check


def integer(lo, hi, default=None):
    def check(v, key):
        x = _number(v, key, lo, hi)
        if x != int(x):
            _fail(key, "must be a whole number")
        return int(x)
    check.default = default
    return check


def text(choices=None, default=None):
    def check(v, key):
        if not isinstance(v, str) or not v.strip():
            _fail(key, "must be text")
        if choices and v not in choices:
            _fail(key, "= '%s' is not one of: %s" % (v, ", ".join(choices)))
        return v
    check.default = default
    return check


def weights(choices, default=None):
    """One name, a list of names (equally likely) or {name: weight}; normalised to {name: probability}."""
    def check(v, key):
        if isinstance(v, str):
            v = [v]
        if isinstance(v, list):
            v = {n: 1.0 for n in v}
        if not isinstance(v, dict) or not v:
            _fail(key, "must be a name, a list of names or {name: weight}")
        for n, w in v.items():
            if n not in choices:
                _fail("%s.%s" % (key, n), "is not one of: %s" % ", ".join(choices))
            _number(w, "%s.%s" % (key, n), 0.0, 1e9)
        total = float(sum(v.values()))
        if total <= 0:
            _fail(key, "has no positive weight")
        return {n: v[n] / total for n in choices if n in v and v[n] > 0}
    check.default = default
    return check


def per_model(lo, hi):
    """{auv model: number} (optional; a model left out has no limit)."""
    def check(v, key):
        if not isinstance(v, dict):
            _fail(key, "must be {model: number}")
        for n in v:
            if n not in AUV_MODELS:
                _fail("%s.%s" % (key, n), "is not one of: %s" % ", ".join(AUV_MODELS))
        return {n: _number(x, "%s.%s" % (key, n), lo, hi) for n, x in v.items()}
    check.default = {}
    return check


def survey_depth(v, key):
    """'plan' (the middle of the target depth band: docs/campaign.md) or a depth distribution."""
    return v if v == "plan" else dist(0.0, 1000.0)(v, key)


survey_depth.default = "plan"


def sites(v, key):
    """{shipped: all | [names], origins: [{name, latitude, longitude}]} -> [{name, latitude, longitude, altitude}]."""
    if not isinstance(v, dict):
        _fail(key, "must be {shipped: all | [names], origins: [...]}")
    for k in v:
        if k not in ("shipped", "origins"):
            _fail("%s.%s" % (key, k), "is not a known key (typo?)")
    out = []
    shipped = v.get("shipped", [])
    if shipped == "all":
        shipped = list(SHIPPED_SITES)
    if not isinstance(shipped, list):
        _fail(key + ".shipped", "must be 'all' or a list of: %s" % ", ".join(SHIPPED_SITES))
    for i, n in enumerate(shipped):
        if n not in SHIPPED_SITES:
            _fail("%s.shipped[%d]" % (key, i), "= '%s' is not one of: %s" % (n, ", ".join(SHIPPED_SITES)))
        with open(os.path.join(REPO, "config", "scenarios", n + ".yaml")) as f:
            o = yaml.safe_load(f)["origin"]
        out.append({"name": n, "latitude": o["latitude"], "longitude": o["longitude"],
                    "altitude": o.get("altitude", 0.0)})
    origins = v.get("origins", [])
    if not isinstance(origins, list):
        _fail(key + ".origins", "must be a list")
    for i, o in enumerate(origins):
        k = "%s.origins[%d]" % (key, i)
        out.append(section(o, k, {"name": text(), "latitude": number(-90, 90), "longitude": number(-180, 180),
                                  "altitude": number(-500, 9000, 0.0)}))
    if not out:
        _fail(key, "names no site")
    names = [s["name"] for s in out]
    if len(set(names)) != len(names):
        _fail(key, "names a site twice")
    return out


def faults(v, key):
    """[{plan: 'NAME@T[+D] ...', probability: p}]: at most one plan per run, plan i with probability p_i."""
    if not isinstance(v, list):
        _fail(key, "must be a list of {plan, probability}")
    out = [section(f, "%s[%d]" % (key, i), {"plan": text(), "probability": number(0.0, 1.0)})
           for i, f in enumerate(v)]
    if sum(f["probability"] for f in out) > 1.0 + 1e-9:
        _fail(key, "probabilities add up to more than 1")
    return out


faults.default = []

# ---------------------------------------------------------------- the schema (docs/campaign.md explains each key)
SCHEMA = {
    "name": text(),
    "purpose": text(("tuning", "evaluation")),
    "seed": integer(1, 2 ** 31 - 1),
    "missions": integer(1, 10 ** 7, 100),
    "site": sites,
    "auv_model": weights(AUV_MODELS, {"girona500": 1.0}),
    "current": {"speed": dist(0, 5, 0.0), "direction_deg": dist(-360, 360, [0.0, 360.0]),
                "variation": dist(0, 2, 0.0), "stem_limit": per_model(0.0, 5.0)},
    "wind": {"speed": dist(0, 40, 0.0), "direction_deg": dist(-360, 360, [0.0, 360.0]), "gust_factor": dist(0, 1, 0.0)},
    # the wind's sea over this fetch, from the wind's direction (the scenario's waves.fetch: models::environment)
    "waves": {"fetch_m": dist(0, 1e7, 0.0)},
    "area": {"distance_m": dist(5, 5000), "bearing_deg": dist(-360, 360, [0.0, 360.0]), "length_m": dist(1, 5000),
             "width_m": dist(1, 5000), "spacing_m": dist(0.5, 1000, 5.0)},
    "usv": {"yaw_deg": dist(-360, 360, [0.0, 360.0])},
    "auv": {"start_offset_m": dist(0, 1000, 7.0), "start_depth_m": dist(0, 1000, 2.0), "survey_depth_m": survey_depth},
    "target": {"depth_m": dist(0.05, 1000), "radius_m": dist(0.05, 20, 0.5)},
    "obstacles": {"count": count(0, 10, 0), "type": weights(OBSTACLE_TYPES, {"buoy": 1.0}),
                  "buoy_radius_m": dist(0.05, 50, 0.6), "buoy_height_m": dist(0.05, 50, 1.0),
                  "vessel_length_m": dist(0.5, 400, 10.0), "vessel_width_m": dist(0.2, 100, 3.0),
                  "vessel_height_m": dist(0.1, 60, 2.0), "along": dist(0, 1, [0.2, 0.8]),
                  "offset_m": dist(-1000, 1000, 0.0), "clearance_m": number(0, 1000, 3.0)},
    "mission": {"max_sim_time": number(10, 86400, 900.0), "hold_time": number(0, 3600, 60.0),
                "target_tolerance": number(0.01, 1000, 2.0)},
    "faults": faults,
}


def section(node, path, schema):
    """Checks a mapping against its schema (unknown keys refused, defaults filled, sub-sections recursed)."""
    if not isinstance(node, dict):
        _fail(path or "(top level)", "must be a mapping")
    for k in node:
        if k not in schema:
            _fail(path + "." + str(k) if path else str(k), "is not a known key (typo?)")
    out = {}
    for k, check in schema.items():
        key = path + "." + k if path else k
        if isinstance(check, dict):
            out[k] = section(node.get(k, {}), key, check)
        elif k in node:
            out[k] = check(node[k], key)
        elif getattr(check, "default", None) is not None:
            out[k] = check.default
        else:
            _fail(key, "is missing")
    return out


def _check_together(s):
    """Rules across keys."""
    if s["purpose"] == "evaluation" and s["seed"] < EVALUATION_SEED_MIN:
        _fail("seed", "= %d is a tuning seed (below %d); an evaluation campaign needs an evaluation seed"
              % (s["seed"], EVALUATION_SEED_MIN))
    if s["purpose"] == "tuning" and s["seed"] >= EVALUATION_SEED_MIN:
        _fail("seed", "= %d is an evaluation seed (%d and above); a tuning campaign needs a seed below it"
              % (s["seed"], EVALUATION_SEED_MIN))
    for m, limit in s["current"]["stem_limit"].items():
        if m in s["auv_model"] and s["current"]["speed"][0] > limit:
            _fail("current.speed", "starts at %g m/s, above the %s's stem_limit %g m/s"
                  % (s["current"]["speed"][0], m, limit))
    if s["target"]["depth_m"][0] < s["target"]["radius_m"][1]:
        _fail("target.depth_m", "must be at least the largest target.radius_m (a target is fully submerged)")
    return s


def validate(doc, missions=None, seed=None):
    """The normalised spec from a parsed YAML document; `missions` / `seed` override the file's."""
    if isinstance(doc, dict):
        doc = dict(doc)
        if missions is not None:
            doc["missions"] = missions
        if seed is not None:
            doc["seed"] = seed
    return _check_together(section(doc, "", SCHEMA))


def load(path, missions=None, seed=None):
    """Validated spec of a file; SpecError("campaign spec 'FILE': key 'K' ...") otherwise."""
    try:
        with open(path) as f:
            doc = yaml.safe_load(f)
        s = validate(doc, missions, seed)
    except (OSError, yaml.YAMLError) as e:
        raise SpecError("campaign spec '%s': %s" % (path, e))
    except SpecError as e:
        raise SpecError("campaign spec '%s': %s" % (path, e))
    s["file"] = os.path.relpath(os.path.abspath(path), REPO) if os.path.abspath(path).startswith(REPO) else path
    return s


def fingerprint(spec):
    """What makes two campaigns the same runs: every key but the mission count and the file's location."""
    same = {k: v for k, v in spec.items() if k not in ("missions", "file")}
    return hashlib.sha256(json.dumps(same, sort_keys=True).encode()).hexdigest()[:16]
