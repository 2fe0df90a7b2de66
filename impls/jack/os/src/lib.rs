//! jack-os
