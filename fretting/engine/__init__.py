"""The incremental state machine: state, the choice of model, stepping, recording and running."""
