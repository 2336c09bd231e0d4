# micron_sim: the Micron head's emulator (core: SeaNet answered like the head, beams drawn by the simulator's sonar
# model) and the MicronEmulator nodelet on a pseudo-terminal. Beside the simulator, so that the driver (micron)
# links neither the simulator nor OpenCV.
