"""seahelm.identification."""
