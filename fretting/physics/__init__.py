"""The contact: profiles, the normal problem and the closed forms of the tangential problem."""
