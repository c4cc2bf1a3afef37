"""The result dataset: its variables and its files."""
