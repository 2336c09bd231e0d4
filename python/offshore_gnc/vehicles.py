"""The vehicles as their manifests describe them (config/vehicles/<vehicle>.yaml, from which the launch files'
component blocks and the ROS-free stacks are built; docs/architecture.md, "Vehicle manifests"): what the Python tools
need of them, so that none keeps its own list of the AUV's models or path to a vehicle's config."""
import os

import yaml

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def manifest(vehicle):
    with open(os.path.join(REPO, "config", "vehicles", vehicle + ".yaml")) as f:
        return yaml.safe_load(f)


def auv_models():
    """The AUV's models, the first the default (auv.launch vehicle_model)."""
    return tuple(manifest("auv")["models"])


def vehicle_config(vehicle, model=""):
    """The vehicle's own config file (what usv.launch and auv.launch load as `config`)."""
    path = manifest(vehicle)["vehicle_config"]["file"].replace("{model}", model).replace("{vehicle}", vehicle)
    return os.path.join(REPO, "config", path)
