"""The reader protocol: what fresh readers are shown (drawn from a seed), what they are told,
and a deterministic scorer of their answers. See docs/readers.md."""
