"""seahelm.environment."""
