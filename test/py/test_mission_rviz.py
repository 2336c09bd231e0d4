"""rviz with the USV configuration, under Xvfb: the planned path and detection markers are drawn.

The screenshot is kept as test/.. docs/images/rviz_usv.png when OFFSHORE_GNC_SAVE_SCREENSHOT is set."""
import os
import shutil
import time

from offshore_gnc.testing import MasterSet
from offshore_gnc.testing.screenshot import RvizScreen, count_colour

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PATH_RGB = (25, 255, 0)     # config/rviz/usv.rviz "Planned path" colour
MARKER_RGB = (255, 40, 40)  # the marker published below

PATH_MSG = {"header": {"frame_id": "map_ned"},
            "poses": [{"pose": {"position": {"x": float(n), "y": 0.0, "z": 0.0}, "orientation": {"w": 1.0}}}
                      for n in range(0, 50, 10)]}
MARKERS = {"markers": [{"header": {"frame_id": "map_ned"}, "ns": "test", "id": 1, "type": 3, "action": 0,
                        "pose": {"position": {"x": 25.0, "y": 6.0, "z": 0.0}, "orientation": {"w": 1.0}},
                        "scale": {"x": 3.0, "y": 3.0, "z": 1.0},
                        "color": {"r": 1.0, "g": 40 / 255.0, "b": 40 / 255.0, "a": 1.0}}]}


def test_rviz_draws_path_and_markers(tmp_path):
    with MasterSet(["usv"]) as ms:
        m = ms["usv"]
        m.set_param("/site/origin", "61.4507,23.7270")
        m.run(["rosrun", "nodelet", "nodelet", "standalone", "offshore_gnc/WorldFrames"], name="frames")
        m.publish("/usv/guidance/planned_path", "nav_msgs/Path", PATH_MSG)
        m.publish("/usv/markers", "visualization_msgs/MarkerArray", MARKERS)
        with RvizScreen(m, os.path.join(REPO, "config", "rviz", "usv.rviz")) as screen:
            png = str(tmp_path / "rviz.png")
            # rviz needs a few seconds to start and draw with the software renderer
            found = (0, 0)
            for _ in range(30):
                time.sleep(1.0)
                screen.shot(png)
                found = (count_colour(png, PATH_RGB), count_colour(png, MARKER_RGB))
                if found[0] > 50 and found[1] > 50:
                    break
        if os.environ.get("OFFSHORE_GNC_SAVE_SCREENSHOT"):
            shutil.copy(png, os.environ["OFFSHORE_GNC_SAVE_SCREENSHOT"])
        assert found[0] > 50, "planned path not drawn (%d green pixels)" % found[0]
        assert found[1] > 50, "detection marker not drawn (%d red pixels)" % found[1]
