"""Test helpers for offshore_gnc: several real ROS masters in one test (see masters.py)."""
from .masters import Master, MasterSet, free_port, run_job  # noqa: F401
from .poll import wait_until  # noqa: F401
