"""The version of fretting, in one place that any module can import (pyproject.toml reads it)."""

__version__ = "0.1.0"
