//! PLACEHOLDER (helper 2 writes integer sine/cosine here).
