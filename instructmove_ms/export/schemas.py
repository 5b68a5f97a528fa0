"""Topics and frame ids of an episode MCAP, and the two messages of our own.

Everything uses Foxglove's well-known protobuf schemas except the action vector and the
episode record, for which no Foxglove schema fits: ``instructmove.Action`` and
``instructmove.Episode`` below (protobuf too, so every channel decodes the same way).
"""

from __future__ import annotations

from google.protobuf import descriptor_pb2, descriptor_pool, message_factory, timestamp_pb2

WORLD = "world"
EPISODE = "/episode"
ACTION = "/robot/action"
LINKS = "/tf"
OBJECTS = "/objects/poses"


def joints_topic(arm: str) -> str:
    return f"/robot/{arm}/joint_states"


def camera_topic(camera: str, kind: str) -> str:
    """``kind``: ``color``, ``depth``, ``calibration`` or ``pose``."""
    return f"/camera/{camera}/{kind}"


def optical_frame(camera: str) -> str:
    """The camera's OpenCV optical frame: x right, y down, z forward."""
    return f"{camera}_optical"


_F = descriptor_pb2.FieldDescriptorProto
_SCALARS = {
    "string": _F.TYPE_STRING,
    "double": _F.TYPE_DOUBLE,
    "bool": _F.TYPE_BOOL,
    "uint32": _F.TYPE_UINT32,
    "int64": _F.TYPE_INT64,
}
_TIMESTAMP = ".google.protobuf.Timestamp"
#: name -> fields as (name, type); "repeated " marks a list.
MESSAGES: dict[str, tuple[tuple[str, str], ...]] = {
    "Action": (
        ("timestamp", _TIMESTAMP),
        ("control_mode", "string"),
        ("names", "repeated string"),
        ("values", "repeated double"),
    ),
    "Episode": (
        ("timestamp", _TIMESTAMP),
        ("env_id", "string"),
        ("robot", "string"),
        ("episode_id", "uint32"),
        ("seed", "int64"),
        ("instruction", "string"),
        ("success", "bool"),
        ("stage_score", "double"),
        ("json", "string"),
    ),
}


def _file_proto() -> descriptor_pb2.FileDescriptorProto:
    proto = descriptor_pb2.FileDescriptorProto(
        name="instructmove/episode.proto",
        package="instructmove",
        syntax="proto3",
        dependency=[timestamp_pb2.DESCRIPTOR.name],
    )
    for name, fields in MESSAGES.items():
        message = proto.message_type.add(name=name)
        for number, (field, kind) in enumerate(fields, start=1):
            repeated = kind.startswith("repeated ")
            kind = kind.removeprefix("repeated ")
            entry = message.field.add(
                name=field,
                number=number,
                label=_F.LABEL_REPEATED if repeated else _F.LABEL_OPTIONAL,
                type=_SCALARS.get(kind, _F.TYPE_MESSAGE),
            )
            if kind not in _SCALARS:
                entry.type_name = kind
    return proto


_POOL = descriptor_pool.Default()
_POOL.AddSerializedFile(_file_proto().SerializeToString())
Action = message_factory.GetMessageClass(_POOL.FindMessageTypeByName("instructmove.Action"))
Episode = message_factory.GetMessageClass(_POOL.FindMessageTypeByName("instructmove.Episode"))
