//! hack-vm
