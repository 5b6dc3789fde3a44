#!/usr/bin/python3
"""Records the node's ~computed_torques for a few seconds and writes a PNG: effort per joint against
time, one panel per joint, with the joint's effort limit from robot_description as dashed lines.

    rosrun spatial_dynamics plot_torques.py [--seconds 5] [--node /dynamics] [--out torques.png]

Live instead: rqt_plot /dynamics/computed_torques/effort[0] /dynamics/computed_torques/effort[1] ...
"""
import argparse
import math
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import rospy  # noqa: E402
from sensor_msgs.msg import JointState  # noqa: E402


def effort_limits(urdf_text):
    """Joint name → effort limit (N m or N) for every joint whose URDF <limit> gives one."""
    limits = {}
    for joint in ET.fromstring(urdf_text).findall("joint"):
        limit = joint.find("limit")
        if limit is not None and limit.get("effort") is not None:
            limits[joint.get("name")] = float(limit.get("effort"))
    return limits


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=5.0, help="how long to record (default 5)")
    parser.add_argument("--node", default="/dynamics", help="the dynamics node's namespace (default /dynamics)")
    parser.add_argument("--out", default="torques.png", help="the PNG to write (default torques.png)")
    args = parser.parse_args(rospy.myargv()[1:])
    if not args.seconds > 0:
        parser.error("--seconds must be positive, not %s" % args.seconds)

    rospy.init_node("plot_torques", anonymous=True)
    topic = args.node.rstrip("/") + "/computed_torques"
    limits = effort_limits(rospy.get_param("robot_description")) if rospy.has_param("robot_description") else {}
    samples, names = [], []  # (stamp, efforts), appended by the subscriber's thread

    def on_torques(msg):
        if not names:
            names.extend(msg.name)
        if list(msg.name) != names:
            return  # a reload changed the joints: keep the first model's series
        samples.append((msg.header.stamp.to_sec(), list(msg.effort)))

    subscriber = rospy.Subscriber(topic, JointState, on_torques, queue_size=1000)
    end = rospy.Time.now() + rospy.Duration(args.seconds)
    while not rospy.is_shutdown() and rospy.Time.now() < end:
        rospy.sleep(0.05)
    subscriber.unregister()
    recorded = list(samples)
    times, efforts = [t for t, _ in recorded], [e for _, e in recorded]
    if not times:
        sys.exit("no message on %s in %.1f s: is the node running and receiving joint_states?" % (topic, args.seconds))

    t0 = times[0]
    columns = 3
    rows = int(math.ceil(len(names) / float(columns)))
    figure, axes = plt.subplots(rows, columns, figsize=(4.2 * columns, 2.4 * rows), sharex=True, squeeze=False)
    for k, name in enumerate(names):
        ax = axes[k // columns][k % columns]
        ax.plot([t - t0 for t in times], [e[k] for e in efforts], color="tab:blue", linewidth=1.2)
        if name in limits:
            for sign in (1, -1):
                ax.axhline(sign * limits[name], color="tab:red", linestyle="--", linewidth=0.9)
        ax.set_title(name, fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.tick_params(labelsize=8)
    for k in range(len(names), rows * columns):
        axes[k // columns][k % columns].axis("off")
    for ax in axes[-1]:
        ax.set_xlabel("time [s]", fontsize=8)
    figure.suptitle("%s: effort per joint [N m or N]; dashed: the URDF's effort limit" % topic, fontsize=10)
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)
    print("wrote %s: %d messages over %.1f s, %d joints" % (args.out, len(times), times[-1] - t0, len(names)))


if __name__ == "__main__":
    main()
