"""The reader protocol: what fresh readers are shown (drawn from a seed), what they are told,
and a deterministic scorer of their answers. See docs/readers.md."""

#: Where sampled instructions come from: the stored sets, training seeds, or half of each.
SOURCES = ("both", "stored", "train")
#: Which of the robot's cameras in-scene material may show an object in: its scene cameras
#: (a wrist camera only where none shows it), or every camera the policy reads.
CAMERAS = ("scene", "every")
#: The resolution policies are trained on, and so the one in-scene and episode material shows
#: by default (square: the cameras' whole view, squeezed).
POLICY_RESOLUTION = 224
