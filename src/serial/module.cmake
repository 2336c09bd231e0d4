# serial: the devices' lines (termios serial ports that reopen a vanished device) and the pseudo-terminals the
# emulators stand in for them with; used by the drivers (usbl, micron) and their simulators. ROS-free, no tools.
