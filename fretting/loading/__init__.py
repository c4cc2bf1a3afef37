"""Load histories ``Q(t)``, ``sigma(t)`` and the history files that describe them."""
