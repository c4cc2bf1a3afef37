"""What a result gives a user: energy, nucleation quantities and cycle counting."""
