# cola2: the Girona500's COLA2 conventions (core: thruster mapping, NavSts -> state) and the Cola2Bridge nodelet.
# Its messages are msg/Cola2*.msg (COLA2's definitions field for field, same md5sums).
