"""seahelm.analysis."""
