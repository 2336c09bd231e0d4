"""The package's own executables (scenario_check, tracking_metrics, ...) in the sourced catkin workspace, run by
path: `rosrun` would walk the package folder with `find`, and in the development workspace that folder holds the
link back to the repository (build/.ws/src/offshore_gnc), which `find` reports as a file system loop."""
import os


class ToolNotFound(Exception):
    pass


def path(name):
    """devel/lib/offshore_gnc/NAME (or an install space's) of the first workspace on CMAKE_PREFIX_PATH having it."""
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        p = os.path.join(prefix, "lib", "offshore_gnc", name)
        if prefix and os.access(p, os.X_OK):
            return p
    raise ToolNotFound("the offshore_gnc tool %s is not in any workspace on CMAKE_PREFIX_PATH: build and source the "
                       "workspace (devel/setup.bash) first" % name)
