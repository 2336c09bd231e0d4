"""rviz under a virtual X server (Xvfb), and a screenshot of it: what a user would see, checked by pixels."""
import os
import subprocess
import time


def free_display():
    for n in range(90, 200):
        if not os.path.exists("/tmp/.X11-unix/X%d" % n) and not os.path.exists("/tmp/.X%d-lock" % n):
            return n
    raise RuntimeError("no free X display number")


class RvizScreen:
    """Xvfb + rviz with a config against one master (a testing.Master). Use as a context manager."""

    def __init__(self, master, config, size=(1280, 900)):
        self.master, self.config, self.size = master, config, size
        self.display = ":%d" % free_display()

    def __enter__(self):
        self.xvfb = self.master.run(["Xvfb", self.display, "-screen", "0", "%dx%dx24" % self.size, "+extension",
                                     "GLX", "+render", "-noreset"], name="xvfb", env={"LD_PRELOAD": ""})
        deadline = time.time() + 10
        while not os.path.exists("/tmp/.X11-unix/X%s" % self.display[1:]) and time.time() < deadline:
            time.sleep(0.1)
        # Debian's rviz is not ours to sanitize: without this, a --sanitize run's LD_PRELOAD hangs its GL start
        env = {"DISPLAY": self.display, "LIBGL_ALWAYS_SOFTWARE": "1", "LD_PRELOAD": ""}
        self.rviz = self.master.run(["rviz", "-d", self.config], name="rviz", env=env)
        return self

    def shot(self, path):
        """Screenshot of the whole virtual screen as PNG."""
        self.shot_async(path).wait(timeout=30)
        return path

    def shot_async(self, path):
        """Starts a screenshot into `path`; returns its process (exit status 0 when the PNG is written)."""
        if self.rviz.poll() is not None:
            raise RuntimeError("rviz exited with %s (log: %s)" % (self.rviz.returncode, self.master.log_path("rviz")))
        return subprocess.Popen(["import", "-display", self.display, "-window", "root", path],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def __exit__(self, *exc):
        from .masters import _kill
        _kill(self.rviz, grace=3)
        _kill(self.xvfb, grace=2)
        return False


BACKGROUND_RGB = (48, 48, 48)  # config/rviz/*.rviz "Background Color": marks the 3-D view on the screen


def _rgb(png):
    import numpy as np
    import matplotlib.image as mpimg
    img = mpimg.imread(png)
    if img.ndim == 2:  # `import` writes a grayscale PNG when the screen is still all black
        img = np.stack([img] * 3, axis=2)
    if img.dtype != np.uint8:
        return (img[..., :3] * 255).round().astype(np.int16)
    return img[..., :3].astype(np.int16)


def _near(img, rgb, tol):
    import numpy as np
    return np.abs(img - np.array(rgb, dtype=np.int16)).max(axis=2) <= tol


def count_colour(png, rgb, tol=40, view_only=True):
    """Pixels of a PNG within `tol` (per channel, 0-255) of the colour rgb; by default only inside rviz's 3-D
    view (the bounding box of its background colour), so that the display icons in the side panels don't count."""
    img = _rgb(png)
    if view_only:
        import numpy as np
        ys, xs = np.nonzero(_near(img, BACKGROUND_RGB, 2))
        if len(xs) == 0:
            return 0
        img = img[ys.min():ys.max() + 1, xs.min():xs.max() + 1]
    return int(_near(img, rgb, tol).sum())
