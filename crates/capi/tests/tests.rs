//! The one integration-test binary of the C library: the C API called as C calls it, C and C++ programs built against it, handles used after their free, and the checked-in header.

mod calls;
mod cpp;
mod dead;
mod header;
