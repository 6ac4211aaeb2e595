"""seahelm.actuators."""
