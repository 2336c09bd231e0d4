"""The closing count of ./scripts/test (python/offshore_gnc/testing/results.py): each distinct test case once, on
result folders built here in the formats the tools write (gtest's XML printer, rosunit's XML runner, catkin's
placeholder, pytest, test/suites/lib/junit.sh): the latter three are produced by the tools themselves."""
import glob
import io
import os
import re
import subprocess
import sys
import unittest

from catkin.test_results import ensure_junit_result_exist, read_junit2
from rosunit.xmlrunner import XMLTestRunner

from offshore_gnc.testing import results

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.path.join(REPO, "python", "offshore_gnc", "testing", "results.py")

# gtest 1.12's XML printer (gtest.cc: PrintXmlUnitTest) for three tests, one of them GTEST_SKIP()ped.
GTEST = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites tests="3" failures="0" disabled="0" errors="0" time="0.002" timestamp="2026-12-04T10:00:00.000" name="AllTests">
  <testsuite name="Geo" tests="3" failures="0" disabled="0" skipped="1" errors="0" time="0.002" timestamp="2026-12-04T10:00:00.000">
    <testcase name="UtmRoundTrip" file="test/unit/geo/test_geo.cpp" line="12" status="run" result="completed" time="0.001" timestamp="2026-12-04T10:00:00.000" classname="Geo" />
    <testcase name="NedFromLla" file="test/unit/geo/test_geo.cpp" line="30" status="run" result="completed" time="0" timestamp="2026-12-04T10:00:00.001" classname="Geo" />
    <testcase name="NeedsGeoid" file="test/unit/geo/test_geo.cpp" line="44" status="run" result="skipped" time="0" timestamp="2026-12-04T10:00:00.001" classname="Geo">
      <skipped message="test/unit/geo/test_geo.cpp:45&#x0A;no geoid model"><![CDATA[test/unit/geo/test_geo.cpp:45
no geoid model]]></skipped>
    </testcase>
  </testsuite>
</testsuites>
"""

# pytest 7's --junitxml: test_c failed, then its fixture's teardown raised (a second element, same case).
PYTEST = """<?xml version="1.0" encoding="utf-8"?><testsuites><testsuite name="pytest" errors="1" failures="1" skipped="1" tests="3" time="0.049" timestamp="2026-12-04T11:27:09.661564" hostname="vm"><testcase classname="test_s" name="test_a" time="0.001" /><testcase classname="test_s" name="test_b" time="0.000"><skipped type="pytest.skip" message="no vcan">/tmp/test_s.py:3: no vcan</skipped></testcase><testcase classname="test_s" name="test_c" time="0.000"><failure message="assert False">test_s.py:8: AssertionError</failure></testcase><testcase classname="test_s" name="test_c" time="0.000"><error message="failed on teardown with &quot;RuntimeError: teardown&quot;">test_s.py:7: RuntimeError</error></testcase></testsuite></testsuites>"""


def _rosunit_xml(path, case_class):
    """What rosunit's XML runner writes for a unittest.TestCase (rostest.rosrun and rostest itself use it)."""
    stream = io.StringIO()
    stream.write('<?xml version="1.0" encoding="utf-8"?>\n')  # rosunit.core.create_xml_runner
    XMLTestRunner(stream=stream).run(unittest.TestLoader().loadTestsFromTestCase(case_class))
    path.write_text(stream.getvalue())


def _rostest_xml(path, test_name, failure=None):
    """rostest's own file: one case test<test-name> of the class rostest.runner.createUnitTest builds."""
    def fn(self):
        if failure:
            self.fail(failure)
    _rosunit_xml(path, type("RosTest", (unittest.TestCase,), {"__module__": "rostest.runner", "test" + test_name: fn}))


class PerceptionSimTest(unittest.TestCase):
    """A rostest script's cases, run here only by rosunit's runner."""
    __test__ = False  # not a case of this pytest file

    def test_lidar_obstacles(self):
        pass

    def test_sonar_target(self):
        pass


def _junit_sh(path, suite, *cases):
    """A suite's file as test/suites/lib/junit.sh writes it; cases are (name, pass|fail|skip[, message])."""
    calls = "".join('junit_case %s "%s" %s "%s"; ' % (suite, c[0], c[1], c[2] if len(c) > 2 else "") for c in cases)
    subprocess.run(["bash", "-c", 'source "%s/test/suites/lib/junit.sh"; %s junit_write %s "%s" || true'
                    % (REPO, calls, suite, path)], check=True)


def _counts(cases):
    return {s: sum(c.status == s for c in cases) for s in (results.PASSED, results.FAILED, results.SKIPPED)}


def _dir(tmp_path):
    d = tmp_path / "test_results" / "offshore_gnc"
    d.mkdir(parents=True)
    return d


def _cli(folder, *args, allow_skip=False):
    env = {k: v for k, v in os.environ.items() if k != "OFFSHORE_GNC_ALLOW_SKIP"}
    if allow_skip:
        env["OFFSHORE_GNC_ALLOW_SKIP"] = "1"
    p = subprocess.run([sys.executable, CLI, str(folder)] + list(args), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, universal_newlines=True, env=env)
    return p.returncode, p.stdout.strip().splitlines()[-1], p.stderr


def test_gtest_cases_counted_once_not_per_suite_total(tmp_path):
    d = _dir(tmp_path)
    (d / "gtest-test_geo.xml").write_text(GTEST)
    assert read_junit2(str(d / "gtest-test_geo.xml")) == (6, 0, 0, 1)  # catkin_test_results: root + child
    assert _counts(results.read_results(str(d.parent))) == {"passed": 2, "failed": 0, "skipped": 1}


def test_gtest_disabled_test_is_skipped(tmp_path):
    d = _dir(tmp_path)
    (d / "gtest-test_geo.xml").write_text(GTEST.replace(
        'status="run" result="completed" time="0" timestamp="2026-12-04T10:00:00.001"',
        'status="notrun" result="suppressed" time="0" timestamp="2026-12-04T10:00:00.001"'))
    assert _counts(results.read_results(str(d.parent))) == {"passed": 1, "failed": 0, "skipped": 2}


def test_pytest_failure_and_teardown_error_are_one_case(tmp_path):
    d = _dir(tmp_path)
    (d / "pytest-test_s.xml").write_text(PYTEST)
    assert _counts(results.read_results(str(d.parent))) == {"passed": 1, "failed": 1, "skipped": 1}


def test_rostest_counted_from_its_rosunit_cases(tmp_path):
    d = _dir(tmp_path)
    _rosunit_xml(d / "rosunit-perception_sim_usv.xml", PerceptionSimTest)
    _rostest_xml(d / "rostest-test_rostest_perception_sim_usv.xml", "perception_sim_usv")
    assert read_junit2(str(d / "rostest-test_rostest_perception_sim_usv.xml"))[0] == 1
    cases = results.read_results(str(d.parent))
    assert _counts(cases) == {"passed": 2, "failed": 0, "skipped": 0}
    assert {c.name.split(".", 1)[1] for c in cases} == {"PerceptionSimTest.test_lidar_obstacles",
                                                        "PerceptionSimTest.test_sonar_target"}


def test_rostest_without_rosunit_file_is_one_failure(tmp_path):
    d = _dir(tmp_path)
    _rostest_xml(d / "rostest-test_rostest_perception_sim_usv.xml", "perception_sim_usv",
                 "test [perception_sim_usv] did not generate test results")
    cases = results.read_results(str(d.parent))
    assert _counts(cases) == {"passed": 0, "failed": 1, "skipped": 0}
    assert "did not generate test results" in cases[0].message


def test_rostest_whose_node_ran_no_case_is_a_failure(tmp_path):
    class NoTests(unittest.TestCase):
        def check_misnamed(self):
            pass
    d = _dir(tmp_path)
    _rosunit_xml(d / "rosunit-no_tests.xml", NoTests)
    _rostest_xml(d / "rostest-test_rostest_no_tests.xml", "no_tests")
    assert _counts(results.read_results(str(d.parent))) == {"passed": 0, "failed": 1, "skipped": 0}


def test_rosunit_setupclass_error_is_a_failure(tmp_path):
    class Broken(unittest.TestCase):
        @classmethod
        def setUpClass(cls):
            raise RuntimeError("no master")

        def test_x(self):
            pass
    d = _dir(tmp_path)
    _rosunit_xml(d / "rosunit-broken.xml", Broken)
    assert "<testcase" not in (d / "rosunit-broken.xml").read_text()  # rosunit writes errors="1" and no case
    _rostest_xml(d / "rostest-test_rostest_broken.xml", "broken")
    assert _counts(results.read_results(str(d.parent))) == {"passed": 0, "failed": 1, "skipped": 0}


def test_rosunit_writes_a_skipped_case_as_a_pass(tmp_path):
    """No trace of the skip in the file, so no count can see it: hence the check below."""
    class Skips(unittest.TestCase):
        @unittest.skipUnless(False, "AUV scenario")
        def test_auv_only(self):
            pass
    path = _dir(tmp_path) / "rosunit-skips.xml"
    _rosunit_xml(path, Skips)
    assert re.search(r'<testcase classname="[^"]*Skips" name="test_auv_only" time="[0-9.]*" />', path.read_text())
    assert _counts(results.read_file(str(path))) == {"passed": 1, "failed": 0, "skipped": 0}


def test_rostest_scripts_do_not_skip():
    """A skipped case in a rostest script would be a silent pass (above): have only the cases that run."""
    scripts = glob.glob(os.path.join(REPO, "test", "rostest", "**", "*.py"), recursive=True)
    scripts += glob.glob(os.path.join(REPO, "test", "unit", "**", "*.py"), recursive=True)
    assert scripts
    bad = [os.path.relpath(f, REPO) for f in scripts
           if re.search(r"unittest\.skip|\bskipTest\(|SkipTest|pytest\.skip", open(f, encoding="utf-8").read())]
    assert not bad, "rostest scripts that skip (rosunit writes a skip as a pass): %s" % bad


def test_malformed_xml_is_a_failure_named_after_the_file(tmp_path):
    d = _dir(tmp_path)
    (d / "rosunit-killed.xml").write_text('<?xml version="1.0" encoding="utf-8"?>\n')  # killed mid-run
    (d / "notes.xml").write_text("<config/>")
    cases = results.read_results(str(d.parent))
    assert _counts(cases) == {"passed": 0, "failed": 2, "skipped": 0}
    assert {c.name for c in cases} == {"offshore_gnc/rosunit-killed.xml", "offshore_gnc/notes.xml"}


def test_catkin_missing_result_placeholder_is_a_failure(tmp_path):
    d = _dir(tmp_path)
    assert not ensure_junit_result_exist(str(d / "gtest-test_can.xml"))  # the binary crashed: catkin's placeholder
    assert os.listdir(str(d)) == ["MISSING-gtest-test_can.xml"]
    cases = results.read_results(str(d.parent))
    assert _counts(cases) == {"passed": 0, "failed": 1, "skipped": 0}
    assert results.category(cases[0]) == "gtest"


def test_catkin_test_without_any_result_file_is_a_failure(tmp_path):
    d = _dir(tmp_path)
    (d / "gtest-test_geo.xml").write_text(GTEST)
    ctest = tmp_path / "CTestTestfile.cmake"
    ctest.write_text("".join(
        'add_test(_ctest_offshore_gnc_gtest_%s "/ws/build/catkin_generated/env_cached.sh" "/usr/bin/python3" '
        '"/usr/share/catkin/cmake/test/run_tests.py" "/ws/build/test_results/offshore_gnc/gtest-%s.xml" '
        '"--return-code" "/ws/devel/lib/offshore_gnc/%s --gtest_output=xml:/ws/build/test_results/offshore_gnc/'
        'gtest-%s.xml")\n' % ((t,) * 4) for t in ("test_geo", "test_can")))
    files = results.ctest_result_files(str(ctest))
    assert files == ["offshore_gnc/gtest-test_geo.xml", "offshore_gnc/gtest-test_can.xml"]
    missing = results.expected_results(str(d.parent), results.read_results(str(d.parent)), {}, files)
    assert [c.name for c in missing] == ["offshore_gnc/gtest-test_can.xml: no result file"]
    rc, last, _ = _cli(d.parent, "--ctest", str(ctest), allow_skip=True)
    assert (rc, last) == (1, "2 passed, 1 failed, 1 skipped")


def test_suites_exit_status_and_missing_files(tmp_path):
    d = _dir(tmp_path)
    _junit_sh(d / "sim_fuzz.xml", "sim_fuzz", ("scenario_fuzz", "pass"))
    _junit_sh(d / "usbl_fuzz.xml", "usbl_fuzz", ("seatrac_fuzz", "pass"))  # then died: exit status 1
    _junit_sh(d / "micron_decode.xml", "micron_decode", ("cli_capture", "fail", "bad line"))
    (d / "gtest-can_vcan.xml").write_text(GTEST)  # can_vcan copies its gtest files under its name
    status = {"sim_fuzz": 0, "usbl_fuzz": 1, "micron_decode": 1, "can_vcan": 0, "models_fuzz": 1, "relay_fuzz": 0}
    cases = results.read_results(str(d.parent))
    extra = results.expected_results(str(d.parent), cases, status)
    assert sorted(c.name for c in extra) == ["models_fuzz: no result file", "relay_fuzz: no result file",
                                             "usbl_fuzz: exited with status 1"]
    assert _counts(cases + extra) == {"passed": 4, "failed": 4, "skipped": 1}
    args = sum((["--suite-status", "%s=%d" % kv] for kv in status.items()), [])
    rc, last, err = _cli(d.parent, *args, allow_skip=True)
    assert (rc, last) == (1, "4 passed, 4 failed, 1 skipped")
    assert "suites: 4 passed, 4 failed, 1 skipped" in err and "FAILED usbl_fuzz: exited with status 1" in err


def test_every_suite_writes_files_under_its_name(tmp_path):
    """scripts/test expects test/suites/NAME.sh's results in NAME.xml or NAME_*.xml: a suite writing elsewhere would
    count as "no result file"."""
    for script in glob.glob(os.path.join(REPO, "test", "suites", "*.sh")):
        suite = os.path.basename(script)[:-3]
        written = re.findall(r'\$out/([\w.-]+\.xml)', open(script, encoding="utf-8").read())
        assert written, script
        d = tmp_path / suite
        d.mkdir()
        for f in written:
            (d / f).write_text("")
        assert sorted(results.suite_files(str(d), suite)) == sorted(set(written)), script


def test_cli_verdict(tmp_path):
    d = _dir(tmp_path)
    only_a = re.sub(r'<testcase classname="test_s" name="test_[bc]".*?</testcase>', "", PYTEST)
    (d / "pytest-test_ok.xml").write_text(only_a.replace('errors="1" failures="1"', 'errors="0" failures="0"'))
    assert _cli(d.parent) == (0, "1 passed, 0 failed, 0 skipped", "pytest: 1 passed, 0 failed, 0 skipped\n")
    (d / "gtest-test_geo.xml").write_text(GTEST)
    rc, last, err = _cli(d.parent)
    assert (rc, last) == (1, "3 passed, 0 failed, 1 skipped") and "skipped: that is a failure" in err
    assert _cli(d.parent, allow_skip=True)[:2] == (0, "3 passed, 0 failed, 1 skipped")
    _rostest_xml(d / "rostest-test_rostest_x.xml", "x", "Test Fixture Nodes ['/usv/usv_manager'] failed to launch")
    assert _cli(d.parent, allow_skip=True)[:2] == (1, "3 passed, 1 failed, 1 skipped")


def test_cli_no_test_ran(tmp_path):
    rc, last, err = _cli(tmp_path)
    assert (rc, last) == (1, "0 passed, 0 failed, 0 skipped") and "no test ran" in err
