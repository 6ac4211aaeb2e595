"""seahelm.vessels."""
