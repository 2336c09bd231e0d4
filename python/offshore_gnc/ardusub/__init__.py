"""ArduSub (MAVLink v2) bridge for the aColor AUV: core.py is the ROS-free logic, ardusub_bridge.py the ROS node."""
