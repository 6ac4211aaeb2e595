"""seahelm.simulation."""
