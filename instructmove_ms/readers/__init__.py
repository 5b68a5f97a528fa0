"""The reader protocol: what fresh readers are shown (drawn from a seed), what they are told,
and a deterministic scorer of their answers. See docs/readers.md."""

#: Where sampled instructions come from: the stored sets, training seeds, or half of each.
SOURCES = ("both", "stored", "train")
