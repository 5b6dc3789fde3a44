#!/usr/bin/python3
"""Publishes joint_states that move every movable joint of robot_description along a smooth
sinusoid inside its limits (positions and their exact time derivatives as velocities)."""
import math
import xml.etree.ElementTree as ET

import rospy
from sensor_msgs.msg import JointState


def movable_joints(urdf_text):
    """(name, centre, amplitude) for every revolute, continuous and prismatic joint."""
    joints = []
    for joint in ET.fromstring(urdf_text).findall("joint"):
        kind = joint.get("type")
        if kind not in ("revolute", "continuous", "prismatic"):
            continue
        limit = joint.find("limit")
        lower = float(limit.get("lower", 0)) if limit is not None else 0.0
        upper = float(limit.get("upper", 0)) if limit is not None else 0.0
        if kind != "continuous" and upper > lower:
            joints.append((joint.get("name"), 0.5 * (lower + upper), 0.4 * (upper - lower)))
        else:
            joints.append((joint.get("name"), 0.0, 0.5))
    return joints


def main():
    rospy.init_node("demo_joint_state_source")
    joints = movable_joints(rospy.get_param("robot_description"))
    rate_hz = rospy.get_param("~rate", 100.0)
    period = rospy.get_param("~period", 8.0)
    publisher = rospy.Publisher("joint_states", JointState, queue_size=10)
    start = rospy.Time.now()
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        now = rospy.Time.now()
        t = (now - start).to_sec()
        msg = JointState()
        msg.header.stamp = now
        for k, (name, centre, amplitude) in enumerate(joints):
            w = 2 * math.pi / period * (1 + 0.1 * k)
            msg.name.append(name)
            msg.position.append(centre + amplitude * math.sin(w * t))
            msg.velocity.append(amplitude * w * math.cos(w * t))
        publisher.publish(msg)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break


if __name__ == "__main__":
    main()
