// Placeholder, filled in by the solver test work.
