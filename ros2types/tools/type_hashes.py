#!/usr/bin/env python3
"""REP-2011 type hashes (RIHS01) of the ROS 2 messages hapticctrl-dds speaks.

ROS 2 Iron and later put each endpoint's type hash in its DDS user data ("typehash=RIHS01_<hex>;",
REP-2016); a node that checks it compares it with its own. The hash is the SHA-256 of a JSON form
of the message's type description (REP-2011: its fields with their type ids, capacities and nested
type names, and every type it refers to, sorted by name; no default values, no constants).

  type_hashes.py --header OUT   writes the C++ table ros2types' type_hash() looks up
  type_hashes.py --check        recomputes hashes ROS 2 publishes and fails on a difference

The definitions below are the .msg files of ROS 2 (rcl_interfaces' builtin_interfaces,
common_interfaces), field by field; the JSON is written as rosidl_generator_type_description
writes it (json.dumps with ', ' and ': ' separators, keys in this order).
"""
import hashlib
import json
import sys

# REP-2011 / type_description_interfaces/msg/FieldType: base type ids; a nested type is 1; a
# fixed array adds 48, a bounded sequence 96, an unbounded sequence 144.
TYPE_IDS = {'int8': 2, 'uint8': 3, 'int16': 4, 'uint16': 5, 'int32': 6, 'uint32': 7, 'int64': 8,
            'uint64': 9, 'float32': 10, 'float64': 11, 'char': 13, 'bool': 15, 'byte': 16,
            'string': 17}
NESTED = 1
UNBOUNDED_SEQUENCE = 144

MESSAGES = {
    'builtin_interfaces/msg/Time': ['int32 sec', 'uint32 nanosec'],
    'std_msgs/msg/Header': ['builtin_interfaces/Time stamp', 'string frame_id'],
    'std_msgs/msg/String': ['string data'],
    'geometry_msgs/msg/Point': ['float64 x', 'float64 y', 'float64 z'],
    'geometry_msgs/msg/Quaternion': ['float64 x', 'float64 y', 'float64 z', 'float64 w'],
    'geometry_msgs/msg/Vector3': ['float64 x', 'float64 y', 'float64 z'],
    'geometry_msgs/msg/Pose': ['Point position', 'Quaternion orientation'],
    'geometry_msgs/msg/PoseStamped': ['std_msgs/Header header', 'Pose pose'],
    'geometry_msgs/msg/Wrench': ['Vector3 force', 'Vector3 torque'],
    'geometry_msgs/msg/WrenchStamped': ['std_msgs/Header header', 'Wrench wrench'],
    'sensor_msgs/msg/JointState': ['std_msgs/Header header', 'string[] name', 'float64[] position',
                                   'float64[] velocity', 'float64[] effort'],
    'diagnostic_msgs/msg/KeyValue': ['string key', 'string value'],
    'diagnostic_msgs/msg/DiagnosticStatus': ['byte level', 'string name', 'string message',
                                             'string hardware_id', 'KeyValue[] values'],
    'diagnostic_msgs/msg/DiagnosticArray': ['std_msgs/Header header', 'DiagnosticStatus[] status'],
}

# The messages whose topics the bridge has (their DDS type names are in the table it looks up).
TOPIC_TYPES = ['geometry_msgs/msg/PoseStamped', 'geometry_msgs/msg/WrenchStamped',
               'sensor_msgs/msg/JointState', 'diagnostic_msgs/msg/DiagnosticArray',
               'std_msgs/msg/String']

# Hashes ROS 2 shows (`ros2 topic info --verbose` prints "Topic type hash"; the Zenoh RMW puts
# them in its key expressions), as public projects record them: --check recomputes each.
PUBLISHED = {
    'std_msgs/msg/String': 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18',
    'std_msgs/msg/Header': 'RIHS01_f49fb3ae2cf070f793645ff749683ac6b06203e41c891e17701b1cb597ce6a01',
    'geometry_msgs/msg/Point':
        'RIHS01_6963084842a9b04494d6b2941d11444708d892da2f4b09843b9c43f42a7f6881',
    'geometry_msgs/msg/Quaternion':
        'RIHS01_8a765f66778c8ff7c8ab94afcc590a2ed5325a1d9a076ffff38fbce36f458684',
    'geometry_msgs/msg/Pose':
        'RIHS01_d501954e9476cea2996984e812054b68026ae0bfae789d9a10b23daf35cc90fa',
    'geometry_msgs/msg/PoseStamped':
        'RIHS01_10f3786d7d40fd2b54367835614bff85d4ad3b5dab62bf8bca0cc232d73b4cd8',
    'geometry_msgs/msg/WrenchStamped':
        'RIHS01_8dc3deaf06b2ab281f9f9a742a8961c328ca7cec16e3fd6586d3a5c83fa78f77',
    'sensor_msgs/msg/JointState':
        'RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e',
    'diagnostic_msgs/msg/DiagnosticArray':
        'RIHS01_5a8a36efb05fb25070fa0fb3810290c0e6cd4862b54a8fb975a1ee8dc55a333e',
}


def field(package, line):
    type_name, name = line.split()
    type_id_offset = 0
    if type_name.endswith('[]'):
        type_name, type_id_offset = type_name[:-2], UNBOUNDED_SEQUENCE
    nested = ''
    if type_name in TYPE_IDS:
        type_id = TYPE_IDS[type_name]
    else:
        type_id = NESTED
        owner, _, short = type_name.rpartition('/')
        nested = f'{owner or package}/msg/{short}'
    return {'name': name, 'type': {'type_id': type_id + type_id_offset, 'capacity': 0,
                                   'string_capacity': 0, 'nested_type_name': nested}}


def description(type_name):
    package = type_name.split('/')[0]
    return {'type_name': type_name, 'fields': [field(package, f) for f in MESSAGES[type_name]]}


def referenced(type_name, found):
    for f in description(type_name)['fields']:
        nested = f['type']['nested_type_name']
        if nested and nested not in found:
            found[nested] = description(nested)
            referenced(nested, found)
    return found


def rihs01(type_name):
    refs = referenced(type_name, {})
    hashable = {'type_description': description(type_name),
                'referenced_type_descriptions': [refs[name] for name in sorted(refs)]}
    text = json.dumps(hashable, separators=(', ', ': '), sort_keys=False)
    return 'RIHS01_' + hashlib.sha256(text.encode('utf-8')).hexdigest()


def dds_type_name(type_name):
    package, _, message = type_name.split('/')
    return f'{package}::msg::dds_::{message}_'


def write_header(path):
    rows = '\n'.join(f'    {{"{dds_type_name(t)}", "{rihs01(t)}"}},' for t in TOPIC_TYPES)
    with open(path, 'w', encoding='utf-8') as out:
        out.write(f'''#pragma once
// Generated by ros2types/tools/type_hashes.py at build time: REP-2011 type hashes of the
// messages hapticctrl-dds has topics of, by DDS type name.
#include <array>
#include <string_view>

namespace hapticctrl::ros2types::generated {{

struct TypeHash {{
  std::string_view dds_type;
  std::string_view rihs01;
}};

inline constexpr std::array<TypeHash, {len(TOPIC_TYPES)}> kTypeHashes{{{{
{rows}
}}}};

}}  // namespace hapticctrl::ros2types::generated
''')


def check():
    wrong = [(t, rihs01(t), h) for t, h in PUBLISHED.items() if rihs01(t) != h]
    for t, got, want in wrong:
        print(f'type_hashes: {t}: computed {got}, ROS 2 publishes {want}', file=sys.stderr)
    for t in TOPIC_TYPES:
        print(f'{t}: {rihs01(t)}')
    print(f'type_hashes: {len(PUBLISHED) - len(wrong)} of {len(PUBLISHED)} published hashes '
          'recomputed')
    return 1 if wrong else 0


def main(argv):
    if len(argv) == 3 and argv[1] == '--header':
        write_header(argv[2])
        return 0
    if len(argv) == 2 and argv[1] == '--check':
        return check()
    print(__doc__, file=sys.stderr)
    return 64


if __name__ == '__main__':
    sys.exit(main(sys.argv))
