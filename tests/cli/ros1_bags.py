#!/usr/bin/python3
"""The reference side of tests/cli/ros1_bag_test.sh: ROS 1 bags written and read by Debian's
python3-rosbag (the ROS 1 library itself, with the message packages python3-sensor-msgs,
python3-nav-msgs, python3-tf2-msgs and python3-geometry-msgs).

    ros1_bags.py write <folder>            the test bags (below), 10 to 100 KiB each
    ros1_bags.py seeds <folder>            the same, a tenth as long: the fuzz target's seeds
    ros1_bags.py compare <bag> <dump>...   rosbag's reading of each <bag> against retrace's (the
                                           JSON lines of retrace_log_dump), field for field;
                                           exit 1 on a difference
    ros1_bags.py refuses <file>...         exit 0 if rosbag refuses to open or read every <file>
    ros1_bags.py reindex <bag> <copy>      a bag without index reindexed by rosbag, as `rosbag
                                           reindex` does it (what rosbag reads of a cut recording)

The bags, written with rosbag.Bag as `rosbag record` writes them (small chunks: several each):
    drive_none.bag, drive_bz2.bag, drive_lz4.bag   1 s of a drive: /scan sensor_msgs/LaserScan
        (181 beams, one without return), /odom nav_msgs/Odometry, /tf tf2_msgs/TFMessage,
        /tf_static, /ground_truth geometry_msgs/PoseStamped
    other_types.bag   /multi_scan sensor_msgs/MultiEchoLaserScan, /tf tf/tfMessage (the old tf
        package's type, made by genpy from its definition), /amcl_pose
        geometry_msgs/PoseWithCovarianceStamped, /odom
    out_of_order.bag  /odom written second half first: chunks stored out of time order
    cut.bag           drive_lz4.bag copied while it was being written: no index, a chunk open
    no_scan.bag       /odom and /chatter std_msgs/String only
    other_md5.bag     /scan of type sensor_msgs/LaserScan with another md5sum
"""
import contextlib
import io
import json
import math
import os
import shutil
import sys

try:
    import genpy
    import genpy.dynamic
    import rosbag
    from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped, TransformStamped
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import LaserEcho, LaserScan, MultiEchoLaserScan
    from std_msgs.msg import String
    from tf2_msgs.msg import TFMessage
except ImportError as e:
    sys.exit(f"ros1_bags.py: {e}: install python3-rosbag, python3-sensor-msgs, python3-nav-msgs, "
             "python3-tf2-msgs and python3-geometry-msgs (scripts/install_deps.sh --test)")

START = 1_600_000_000  # s: stamps and record times from here


def stamp(k, rate_hz):
    ns = round(k * 1e9 / rate_hz)
    return genpy.Time(START + ns // 1_000_000_000, ns % 1_000_000_000)


def quaternion(yaw):
    return 0.0, 0.0, math.sin(0.5 * yaw), math.cos(0.5 * yaw)


def set_pose(pose, x, y, yaw):
    pose.position.x, pose.position.y = x, y
    q = pose.orientation
    q.x, q.y, q.z, q.w = quaternion(yaw)


def scan(t, k):
    s = LaserScan()
    s.header.stamp, s.header.frame_id = t, 'laser'
    s.angle_min, s.angle_increment = -math.pi / 2, math.pi / 180
    s.angle_max = s.angle_min + 180 * s.angle_increment
    s.range_min, s.range_max, s.scan_time = 0.1, 30.0, 0.1
    s.ranges = [2.0 + 0.01 * i + 0.001 * k for i in range(181)]
    s.ranges[90] = math.inf  # no return
    s.intensities = [100.0] * 181
    return s


def odometry(t, k):
    o = Odometry()
    o.header.stamp, o.header.frame_id, o.child_frame_id = t, 'odom', 'base_link'
    set_pose(o.pose.pose, 0.02 * k, 0.001 * k * k, 0.01 * k)
    o.twist.twist.linear.x = 1.0
    return o


def transform(t, parent, child, x, yaw):
    ts = TransformStamped()
    ts.header.stamp, ts.header.frame_id, ts.child_frame_id = t, parent, child
    ts.transform.translation.x = x
    q = ts.transform.rotation
    q.x, q.y, q.z, q.w = quaternion(yaw)
    return ts


def write_drive(bag, steps):
    bag.write('/tf_static', TFMessage([transform(stamp(0, 1), 'base_link', 'laser', 0.2, 0.0)]),
              stamp(0, 1))
    for k in range(steps):  # 50 Hz
        t = stamp(k, 50)
        bag.write('/odom', odometry(t, k), t)
        bag.write('/tf', TFMessage([transform(t, 'odom', 'base_link', 0.02 * k, 0.01 * k)]), t)
        truth = PoseStamped()
        truth.header.stamp, truth.header.frame_id = t, 'world'
        set_pose(truth.pose, 1.0 + 0.02 * k, -2.0, 0.5 + 0.01 * k)
        bag.write('/ground_truth', truth, t)
        if k % 5 == 0:
            bag.write('/scan', scan(t, k), t)


def write_other_types(bag, steps):
    tf_message = genpy.dynamic.generate_dynamic('tf/tfMessage', TFMessage._full_text)['tf/tfMessage']
    for k in range(steps):  # 10 Hz
        t = stamp(k, 10)
        m = MultiEchoLaserScan()
        m.header.stamp, m.header.frame_id = t, 'laser'
        m.angle_min, m.angle_increment, m.angle_max = -0.5, 0.25, 0.5
        m.range_min, m.range_max = 0.1, 10.0
        m.ranges = [LaserEcho([1.0 + k, 5.0]), LaserEcho([]), LaserEcho([2.5]), LaserEcho([3.0, 4.0]),
                    LaserEcho([0.5])]
        m.intensities = [LaserEcho([1.0])] * 5
        bag.write('/multi_scan', m, t)
        bag.write('/tf', tf_message([transform(t, 'odom', 'base_link', 0.1 * k, 0.0)]), t)
        bag.write('/odom', odometry(t, k), t)
        amcl = PoseWithCovarianceStamped()
        amcl.header.stamp, amcl.header.frame_id = t, 'map'
        set_pose(amcl.pose.pose, 3.0, 0.1 * k, -0.2)
        amcl.pose.covariance = [0.01 * i for i in range(36)]
        bag.write('/amcl_pose', amcl, t)


def write_bags(folder, scale=1.0):
    """The test bags; scale < 1 makes them shorter (chunks smaller alike)."""
    kib = max(1, round(16 * scale)) * 1024
    for compression in ('none', 'bz2', 'lz4'):
        with rosbag.Bag(f'{folder}/drive_{compression}.bag', 'w', compression=compression,
                        chunk_threshold=kib) as bag:
            write_drive(bag, round(50 * scale))
    with rosbag.Bag(f'{folder}/other_types.bag', 'w', chunk_threshold=kib // 4) as bag:
        write_other_types(bag, round(20 * scale))
    with rosbag.Bag(f'{folder}/out_of_order.bag', 'w', chunk_threshold=kib // 16) as bag:
        n = round(100 * scale)
        for k in list(range(n // 2, n)) + list(range(n // 2)):
            bag.write('/odom', odometry(stamp(k, 50), k), stamp(k, 50))
    # A recording cut off: the file as it is while rosbag is still writing it.
    bag = rosbag.Bag(f'{folder}/unfinished.bag', 'w', compression='lz4', chunk_threshold=kib)
    write_drive(bag, round(50 * scale))
    bag._file.flush()
    shutil.copyfile(f'{folder}/unfinished.bag', f'{folder}/cut.bag')
    bag.close()
    os.remove(f'{folder}/unfinished.bag')
    with rosbag.Bag(f'{folder}/no_scan.bag', 'w') as bag:
        for k in range(max(2, round(10 * scale))):
            bag.write('/odom', odometry(stamp(k, 10), k), stamp(k, 10))
            bag.write('/chatter', String(f'hello {k}'), stamp(k, 10))
    with rosbag.Bag(f'{folder}/other_md5.bag', 'w') as bag, \
            contextlib.redirect_stderr(io.StringIO()):  # rosbag warns of the md5sum it is given
        s = scan(stamp(0, 10), 0)
        raw = (LaserScan._type, serialized(s), '0123456789abcdef0123456789abcdef', LaserScan)
        bag.write('/scan', raw, stamp(0, 10), raw=True)


def serialized(message):
    buffer = io.BytesIO()
    message.serialize(buffer)
    return buffer.getvalue()


# ---- rosbag's reading, in the form of retrace_log_dump's lines ----------------------------

def number(v):
    v = float(v)
    if math.isnan(v):
        return 'nan'
    if math.isinf(v):
        return 'inf' if v > 0 else '-inf'
    return v


def seconds(t):  # as retrace: sec + nsec * 1e-9
    return t.secs + t.nsecs * 1e-9


def yaw(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def pose_fields(p):
    return {'x': p.position.x, 'y': p.position.y, 'yaw': yaw(p.orientation)}


def fields(type_name, m):
    if type_name in ('sensor_msgs/LaserScan', 'sensor_msgs/MultiEchoLaserScan'):
        if type_name == 'sensor_msgs/LaserScan':
            ranges = m.ranges
        else:
            ranges = [e.echoes[0] if e.echoes else math.inf for e in m.ranges]
        return {'stamp': seconds(m.header.stamp), 'frame_id': m.header.frame_id,
                'angle_min': number(m.angle_min), 'angle_increment': number(m.angle_increment),
                'range_min': number(m.range_min), 'range_max': number(m.range_max),
                'ranges': [number(r) for r in ranges]}
    if type_name == 'nav_msgs/Odometry':
        return {'stamp': seconds(m.header.stamp), 'frame_id': m.header.frame_id,
                'child_frame_id': m.child_frame_id, **pose_fields(m.pose.pose)}
    if type_name in ('tf2_msgs/TFMessage', 'tf/tfMessage'):
        return {'transforms': [
            {'stamp': seconds(t.header.stamp), 'parent': t.header.frame_id, 'child': t.child_frame_id,
             'x': t.transform.translation.x, 'y': t.transform.translation.y,
             'yaw': yaw(t.transform.rotation)} for t in m.transforms]}
    if type_name == 'geometry_msgs/PoseStamped':
        return {'stamp': seconds(m.header.stamp), 'frame_id': m.header.frame_id,
                **pose_fields(m.pose)}
    if type_name == 'geometry_msgs/PoseWithCovarianceStamped':
        return {'stamp': seconds(m.header.stamp), 'frame_id': m.header.frame_id,
                **pose_fields(m.pose.pose)}
    return {'bytes': len(serialized(m))}


def same(a, b, path):
    """The differences between rosbag's value a and retrace's b (yaws to 1e-12, the rest exact)."""
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            return [f'{path}: fields {sorted(a)} vs {sorted(b)}']
        return [d for k in a for d in same(a[k], b[k], f'{path}.{k}')]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f'{path}: {len(a)} vs {len(b)} elements']
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in same(x, y, f'{path}[{i}]')]
    if path.endswith('.yaw') and isinstance(a, float) and isinstance(b, (int, float)):
        return [] if abs(a - b) <= 1e-12 else [f'{path}: {a!r} vs {b!r}']
    if isinstance(a, float) and isinstance(b, int):
        b = float(b)
    return [] if a == b else [f'{path}: {a!r} vs {b!r}']


def definition_errors(bag):
    """Each connection's md5sum against its type's: the installed message class's, and the one
    genpy computes from the connection's message definition."""
    errors = []
    for c in bag._connections.values():
        computed = genpy.dynamic.generate_dynamic(c.datatype, c.msg_def)[c.datatype]._md5sum
        installed = genpy.message.get_message_class(c.datatype)
        expected = installed._md5sum if installed else computed
        if not c.md5sum == computed == expected:
            errors.append(f'{c.topic} ({c.datatype}): md5sum {c.md5sum}, of its definition '
                          f'{computed}, of the installed type {expected}')
    return errors


def compare(bag_file, dump_file):
    """rosbag's messages of each topic against retrace's, in order; and retrace's in time order."""
    with open(dump_file) as f:
        dumped = [json.loads(line) for line in f]
    times = [d['time_ns'] for d in dumped]
    errors = [] if times == sorted(times) else ['retrace: messages not in time order']
    ours = {}
    for d in dumped:
        ours.setdefault(d.pop('topic'), []).append(d)
    theirs = {}
    with rosbag.Bag(bag_file) as bag:
        errors += definition_errors(bag)
        for topic, m, t, header in bag.read_messages(return_connection_header=True):
            # The connection's type: rosbag keeps one class per md5sum, so a tf/tfMessage may
            # come as the tf2_msgs/TFMessage class read before it.
            type_name = header['type'].decode()
            line = fields(type_name, m)
            line.update({'type': type_name, 'time_ns': t.to_nsec()})
            theirs.setdefault(topic, []).append(line)
    # In time order, as retrace hands them out. (rosbag's Python reader keeps each connection's
    # chunks in the order they are stored: for chunks stored out of time order it is not.)
    for messages in theirs.values():
        messages.sort(key=lambda m: m['time_ns'])
    if sorted(ours) != sorted(theirs):
        errors.append(f'topics: rosbag {sorted(theirs)}, retrace {sorted(ours)}')
    for topic in sorted(set(ours) & set(theirs)):
        errors += same(theirs[topic], ours[topic], topic)
    for e in errors[:20]:
        print(f'{bag_file}: {e}')
    count = sum(len(v) for v in theirs.values())
    print(f'{bag_file}: {count} messages on {len(theirs)} topics compared, {len(errors)} differences')
    return 1 if errors else 0


def refuses(file):
    try:
        with rosbag.Bag(file) as bag:
            for _ in bag.read_messages():
                pass
    except Exception as e:  # rosbag raises ROSBagException and its subclasses, struct.error, ...
        print(f'{file}: rosbag refuses it: {type(e).__name__}: {e}')
        return 0
    print(f'{file}: rosbag read it')
    return 1


def reindex(bag_file, copy):
    shutil.copyfile(bag_file, copy)
    with rosbag.Bag(copy, 'a', allow_unindexed=True) as bag:
        for _ in bag.reindex():
            pass
    return 0


if __name__ == '__main__':
    args = sys.argv[2:]
    if len(args) == 1 and sys.argv[1] == 'write':
        write_bags(args[0])
    elif len(args) == 1 and sys.argv[1] == 'seeds':
        write_bags(args[0], 0.1)
    elif args and len(args) % 2 == 0 and sys.argv[1] == 'compare':
        sys.exit(max(compare(args[i], args[i + 1]) for i in range(0, len(args), 2)))
    elif args and sys.argv[1] == 'refuses':
        sys.exit(max(refuses(f) for f in args))
    elif len(sys.argv) == 4 and sys.argv[1] == 'reindex':
        sys.exit(reindex(sys.argv[2], sys.argv[3]))
    else:
        sys.exit(__doc__)
