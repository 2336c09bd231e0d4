"""Repository rules that keep the design honest: the core stays ROS-free, CI runs the README's command."""
import glob
import os
import re
import subprocess

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ROS_INCLUDE = re.compile(
    r'#\s*include\s*[<"](ros|nodelet|pluginlib|tf2_ros|tf2_geometry_msgs|tf2_eigen|\w+_msgs|diagnostic_updater|'
    r'topic_tools|rosbag|cv_bridge|pcl_ros|pcl_conversions|dynamic_reconfigure|image_transport|message_filters|'
    r'offshore_gnc/ros|offshore_gnc/[A-Z]\w*\.h)[/">]')


def _core_files():
    files = [f for f in glob.glob(os.path.join(REPO, "include", "offshore_gnc", "**", "*.h*"), recursive=True)
             if os.sep + "ros" + os.sep not in f]
    for f in glob.glob(os.path.join(REPO, "src", "*", "*.cpp")):
        b = os.path.basename(f)
        if b.endswith(("_nodelet.cpp", "_main.cpp", "_bench.cpp", "_fuzz.cpp")) or b.startswith("ros_"):
            continue
        files.append(f)
    return files


def test_core_sources_do_not_include_ros():
    files = _core_files()
    assert files, "no core files found"
    bad = []
    for f in files:
        for n, line in enumerate(open(f, encoding="utf-8"), 1):
            if ROS_INCLUDE.search(line):
                bad.append("%s:%d: %s" % (os.path.relpath(f, REPO), n, line.strip()))
    assert not bad, "ROS includes in the ROS-free core:\n" + "\n".join(bad)


def test_the_check_itself_catches_ros_includes():
    for line in ["#include <ros/ros.h>", '#include "sensor_msgs/PointCloud2.h"', "#include <offshore_gnc/Target.h>",
                 "#include <offshore_gnc/ros/params.h>", "#include <tf2_ros/buffer.h>"]:
        assert ROS_INCLUDE.search(line), line
    for line in ["#include <Eigen/Core>", '#include "offshore_gnc/geo/geo.h"', "#include <GeographicLib/UTMUPS.hpp>"]:
        assert not ROS_INCLUDE.search(line), line


def test_core_library_links_no_ros():
    libs = glob.glob(os.path.join(REPO, "build", ".ws*", "devel", "lib", "liboffshore_gnc_core.so"))
    libs += [os.path.join(d, "liboffshore_gnc_core.so") for d in os.environ.get("LD_LIBRARY_PATH", "").split(":") if d]
    libs = [l for l in libs if os.path.exists(l)]
    assert libs, "liboffshore_gnc_core.so not built"
    out = subprocess.run(["ldd", libs[0]], stdout=subprocess.PIPE, check=True).stdout.decode()
    assert not re.search(r"lib(roscpp|rosconsole|rostime|nodeletlib|tf2_ros)", out), out


def test_ci_runs_the_readme_test_command():
    readme = open(os.path.join(REPO, "README.md"), encoding="utf-8").read()
    ci = open(os.path.join(REPO, ".ci", "run"), encoding="utf-8").read()
    cmds = re.findall(r"\./scripts/test\b", readme)
    assert cmds, "README names no test command"
    assert "./scripts/test" in ci


def test_ci_never_accepts_skips():
    """The one opt-out for tests whose real part cannot run (OFFSHORE_GNC_ALLOW_SKIP) is the user's, never CI's."""
    ci = open(os.path.join(REPO, ".ci", "run"), encoding="utf-8").read()
    assert "OFFSHORE_GNC_ALLOW_SKIP" not in ci
    readme = open(os.path.join(REPO, "README.md"), encoding="utf-8").read()
    assert "OFFSHORE_GNC_ALLOW_SKIP=1" in readme  # documented
