import os
import sys

# Let the tests import the harness from the source tree too (before the workspace's devel space exists).
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))
