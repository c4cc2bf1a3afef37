"""Studies of many contacts: sweeps over a parameter grid."""
