"""seahelm.control."""
