"""What every command shares: the argument parser's common parts, one-line errors, atomic output files."""
