"""Discretisations of the tangential problem behind one contract (`fretting.models.base`)."""
