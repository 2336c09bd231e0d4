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


def _built_libs():
    """The module libraries of the workspace under test (the one on LD_LIBRARY_PATH, else any built one)."""
    dirs = [d for d in os.environ.get("LD_LIBRARY_PATH", "").split(":") if d]
    dirs += glob.glob(os.path.join(REPO, "build", ".ws*", "devel", "lib"))
    for d in dirs:
        libs = glob.glob(os.path.join(d, "liboffshore_gnc_*.so"))
        if libs:
            return libs
    return []


def test_core_libraries_link_no_ros():
    modules = set(_module_graph()) - {"ros"}  # liboffshore_gnc_ros is the shared ROS helpers
    core = [l for l in _built_libs() if os.path.basename(l)[len("liboffshore_gnc_"):-len(".so")] in modules]
    assert core, "no offshore_gnc core library built"
    for lib in core:
        out = subprocess.run(["ldd", lib], stdout=subprocess.PIPE, check=True).stdout.decode()
        assert not re.search(r"lib(roscpp|rosconsole|rostime|nodeletlib|tf2_ros)", out), (lib, out)


TEST_CODE = re.compile(r"LLVMFuzzerTestOneInput|fuzz_check|synthetic_scenes|scripted_bus|ScriptedPeer|std::abort")


def test_no_test_code_in_the_product_sources():
    """Test support and fuzz targets live in test/ (test/support/<module>/, test/fuzz/): nothing under src/ or
    include/ (the libraries and the installed headers) is or includes one. Benchmarks (*_bench.cpp) may use test
    support: they are tools, linked into no library."""
    bad = []
    for f in glob.glob(os.path.join(REPO, "src", "**", "*"), recursive=True) + \
            glob.glob(os.path.join(REPO, "include", "**", "*"), recursive=True):
        if not os.path.isfile(f) or f.endswith("_bench.cpp"):
            continue
        rel = os.path.relpath(f, REPO)
        if "fuzz" in os.path.basename(f):
            bad.append(rel + ": a fuzz target (test/fuzz/)")
            continue
        for n, line in enumerate(open(f, encoding="utf-8"), 1):
            if TEST_CODE.search(line) and not line.lstrip().startswith("//"):
                bad.append("%s:%d: %s" % (rel, n, line.strip()))
    assert not bad, "test code in the product:\n" + "\n".join(bad)


def test_no_library_holds_test_code():
    """The built libraries (what is installed) define no fuzz entry point, scripted peer or fuzz invariant."""
    libs = _built_libs()
    assert libs, "no offshore_gnc library built"
    bad = []
    for lib in libs:
        out = subprocess.run(["nm", "-DC", "--defined-only", lib], stdout=subprocess.PIPE, check=True).stdout.decode()
        bad += ["%s: %s" % (os.path.basename(lib), l.strip()) for l in out.splitlines()
                if re.search(r"fuzz|ScriptedPeer|synthetic|LLVMFuzzer", l, re.I)]
    assert not bad, "test code in installed libraries:\n" + "\n".join(bad[:20])


def test_the_test_code_check_itself():
    for line in ['#include "relay/fuzz_check.h"', "  std::abort();", "ScriptedPeer peer(fd, key);"]:
        assert TEST_CODE.search(line), line
    assert not TEST_CODE.search('#include "offshore_gnc/relay/engine.h"')


INLINE_READ = re.compile(r'\b[A-Za-z_]\w*(?:\.|->)(number|requiredNumber|integer|flag|text|choice|numbers)\(\s*"')


def test_parameters_are_read_through_tables():
    """A ROS file reads its parameters through a table (ros_util::readParams / readEntry), never one by one (name,
    default and range written at the read would reach no table, no docs/parameters.md and no .cfg check)."""
    found = []
    for f in glob.glob(os.path.join(REPO, "src", "*", "*")):
        b = os.path.basename(f)
        if not (b.endswith(("_nodelet.cpp", "_main.cpp")) or b.startswith("ros_")):
            continue
        found += ["%s:%d: %s" % (os.path.relpath(f, REPO), n, line.strip())
                  for n, line in enumerate(open(f, encoding="utf-8"), 1) if INLINE_READ.search(line)]
    assert not found, "parameters read outside a table (make them a struct's table()):\n" + "\n".join(found)


def test_the_inline_read_check_itself():
    for line in ['  c.port = p.text("port", "/dev/ttyUSB0");', 'x = reader->number("rate", 1.0, 0, 10);']:
        assert INLINE_READ.search(line), line
    for line in ['      .number("rate", &P::rate, 0, 10, "Hz", "a rate")', 'ros_util::readParams(p, P::table(), c);']:
        assert not INLINE_READ.search(line), line


MAX_LINES = 600


def test_no_source_file_is_too_long():
    """No file under src/, include/, python/ is over MAX_LINES lines: past that a file holds more than one thing."""
    long_files = []
    for top in ("src", "include", "python"):
        for f in glob.glob(os.path.join(REPO, top, "**", "*"), recursive=True):
            if os.path.isfile(f) and not f.endswith(".pyc"):
                with open(f, encoding="utf-8", errors="replace") as fh:
                    if sum(1 for _ in fh) > MAX_LINES:
                        long_files.append(os.path.relpath(f, REPO))
    assert not long_files, "files over %d lines (split them by what they do): %s" % (MAX_LINES, sorted(long_files))


def _module_graph():
    """{module: [dependencies]} from the module graph in CMakeLists.txt (the one place that states it)."""
    text = open(os.path.join(REPO, "CMakeLists.txt"), encoding="utf-8").read()
    graph = {}
    for name, deps in re.findall(r"^offshore_gnc_module\((\w+)(?: DEPENDS ([\w ]+))?\)", text, re.M):
        graph[name] = deps.split() if deps else []
    return graph


def _closure(graph, m):
    seen, todo = set(), [m]
    while todo:
        for d in graph[todo.pop()]:
            if d not in seen:
                seen.add(d)
                todo.append(d)
    return seen


def test_core_includes_follow_the_module_graph():
    """A core file of module M includes only M's own headers and those of modules M depends on (layers point
    down); ROS sides may also use the shared ROS helpers (`ros`)."""
    graph = _module_graph()
    assert {"common", "guidance", "control", "closed_loop"} <= set(graph), graph
    inc = re.compile(r'#\s*include\s*"offshore_gnc/(\w+)/')
    bad = []
    for m in graph:
        allowed = _closure(graph, m) | {m}
        files = glob.glob(os.path.join(REPO, "include", "offshore_gnc", m, "*.h")) + glob.glob(os.path.join(REPO, "src", m, "*.*"))
        for f in files:
            ros_side = os.path.basename(f).startswith("ros_") or f.endswith(("_nodelet.cpp", "_main.cpp"))
            for n, line in enumerate(open(f, encoding="utf-8"), 1):
                hit = inc.search(line)
                if hit and hit.group(1) not in allowed and not (ros_side and hit.group(1) == "ros"):
                    bad.append("%s:%d includes %s (module %s may use %s)" % (
                        os.path.relpath(f, REPO), n, hit.group(1), m, ", ".join(sorted(allowed))))
    assert not bad, "includes that break the layering:\n" + "\n".join(bad)


def test_control_and_guidance_do_not_reach_into_each_other():
    for m, other in (("control", ("guidance", "sim")), ("guidance", ("control",))):
        for f in glob.glob(os.path.join(REPO, "src", m, "*")) + glob.glob(os.path.join(REPO, "include", "offshore_gnc", m, "*")):
            text = open(f, encoding="utf-8").read()
            for o in other:
                assert ("offshore_gnc/%s/" % o) not in text and ("../%s/" % o) not in text, (f, o)


def test_unit_test_files_follow_the_pattern():
    """test/unit/<module>/test_*.cpp is what CMake builds: a file named otherwise would silently not run."""
    graph = _module_graph()
    odd = []
    for f in glob.glob(os.path.join(REPO, "test", "unit", "*", "*.cpp")):
        mod = os.path.basename(os.path.dirname(f))
        if not os.path.basename(f).startswith("test_") or mod not in graph:
            odd.append(os.path.relpath(f, REPO))
    assert not odd, "unit test files CMake does not build: %s" % odd


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
