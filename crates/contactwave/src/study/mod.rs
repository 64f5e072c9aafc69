//! Parameter studies: sweeps over dotted scenario keys.
