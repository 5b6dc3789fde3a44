#!/usr/bin/env python3
"""A Python user of spatial_dynamics in another package: calls the node's ~inverse_dynamics through
the generated service module (spatial_dynamics.srv) and through the package's client
(spatial_dynamics.client), checks that both give the same torques, and checks them against a second
computation by the node: tau = M(q) qdd + ID(q, qd, 0) (~mass_matrix) and ID(FD(tau)) = tau
(~forward_dynamics); and the library's own inverse dynamics through the bindings
(spatial_dynamics.dynamics) against the node's.

    check_inverse_dynamics.py [--node /dynamics] [--prefix DIR]

--prefix: fail unless the spatial_dynamics modules are loaded from below DIR (the install space).
Prints one line per check ("PASS ..." or "FAIL ..."); the exit status is non-zero when any failed.
"""
import argparse
import os
import random
import sys
import xml.etree.ElementTree as ElementTree

import numpy as np
import rospkg
import rospy

import spatial_dynamics.client
import spatial_dynamics.srv
from spatial_dynamics import dynamics
from spatial_dynamics.client import DynamicsClient
from spatial_dynamics.srv import InverseDynamics, InverseDynamicsRequest

TOLERANCE = 1e-12  # relative to the torques' size (at least 1 N m), as in the C++ check

failures = 0


def report(ok, what, error=None):
    global failures
    detail = '' if error is None else ': max error %.3g (bound %.3g)' % (error, TOLERANCE)
    print('%s %s%s' % ('PASS' if ok else 'FAIL', what, detail))
    sys.stdout.flush()
    if not ok:
        failures += 1


def moving_joints(urdf):
    """(name, lower, upper) of the URDF's moving joints (limits None when unbounded)."""
    joints = []
    for joint in ElementTree.parse(urdf).getroot().iter('joint'):
        if joint.get('type') in ('fixed', 'floating', 'planar'):
            continue
        limit = joint.find('limit')
        bounded = joint.get('type') != 'continuous' and limit is not None
        joints.append((joint.get('name'), float(limit.get('lower', 0.0)) if bounded else None,
                       float(limit.get('upper', 0.0)) if bounded else None))
    return joints


def states(joints, count):
    rng = random.Random(20240611)
    for _ in range(count):
        q, qd, qdd = {}, {}, {}
        for name, lower, upper in joints:
            q[name] = rng.uniform(-1.0, 1.0) if lower is None else lower + rng.uniform(0.05, 0.95) * (upper - lower)
            qd[name] = rng.uniform(-1.0, 1.0)
            qdd[name] = rng.uniform(-2.0, 2.0)
        yield q, qd, qdd


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--node', default='/dynamics')
    parser.add_argument('--prefix', default=None)
    args = parser.parse_args(rospy.myargv()[1:])
    rospy.init_node('dynamics_user_check_py', anonymous=True, disable_signals=True)

    modules = [spatial_dynamics.client.__file__, spatial_dynamics.srv.__file__, dynamics.__file__]
    print('modules: %s' % ', '.join(modules))
    if args.prefix is not None:
        prefix = os.path.realpath(args.prefix) + os.sep
        report(all(os.path.realpath(m).startswith(prefix) for m in modules),
               'the spatial_dynamics Python modules come from %s' % args.prefix)

    urdf = os.path.join(rospkg.RosPack().get_path('spatial_dynamics'), 'urdf', 'panda.urdf')
    joints = moving_joints(urdf)
    print('model %s: %d moving joints' % (urdf, len(joints)))
    client = DynamicsClient(args.node)
    client.wait_for_services(timeout=30.0)
    proxy = rospy.ServiceProxy(client.service_name('inverse_dynamics'), InverseDynamics)

    model = dynamics.Model.from_urdf(urdf)
    error_same = error_split = error_round_trip = error_bindings = 0.0
    samples = list(states(joints, 20))
    for q, qd, qdd in samples:
        names = [name for name, _, _ in joints]
        raw = proxy(InverseDynamicsRequest(name=names, position=[q[n] for n in names],
                                           velocity=[qd[n] for n in names], acceleration=[qdd[n] for n in names]))
        if not raw.success or sorted(raw.name) != sorted(names):
            report(False, 'InverseDynamics answered: success %s, %r' % (raw.success, raw.message))
            return 1
        tau_raw = dict(zip(raw.name, raw.effort))
        tau = client.inverse_dynamics(position=q, velocity=qd, acceleration=qdd)
        order = tau.names
        tau_vec = tau.as_array()
        scale = max(1.0, float(np.max(np.abs(tau_vec))))
        error_same = max(error_same, max(abs(tau_raw[n] - tau[n]) for n in order) / scale)

        bias = client.inverse_dynamics(position=q, velocity=qd).as_array()  # acceleration 0
        mass = client.mass_matrix(position=q)
        index = {n: k for k, n in enumerate(mass.names)}
        m = mass.as_array()[np.ix_([index[n] for n in order], [index[n] for n in order])]
        expected = m.dot(np.array([qdd[n] for n in order])) + bias
        error_split = max(error_split, float(np.max(np.abs(tau_vec - expected))) / scale)

        vector = lambda values: np.array([values[n] for n in model.joint_names])  # the model's order
        tau_bindings = dict(zip(model.joint_names, model.rnea(vector(q), vector(qd), vector(qdd))))
        error_bindings = max(error_bindings, max(abs(tau_bindings[n] - tau[n]) for n in order) / scale)

        qdd_fd = client.forward_dynamics(position=q, velocity=qd, effort=dict(zip(order, tau_vec)))
        tau_back = client.inverse_dynamics(position=q, velocity=qd, acceleration=dict(qdd_fd)).as_array()
        error_round_trip = max(error_round_trip, float(np.max(np.abs(tau_back - tau_vec))) / scale)

    report(error_same <= TOLERANCE, 'spatial_dynamics.srv.InverseDynamics = DynamicsClient.inverse_dynamics (%d states)'
           % len(samples), error_same)
    report(error_split <= TOLERANCE, 'inverse_dynamics = mass_matrix * qdd + inverse_dynamics(qdd = 0) (%d states)'
           % len(samples), error_split)
    report(error_round_trip <= TOLERANCE, 'inverse_dynamics(forward_dynamics(tau)) = tau (%d states)' % len(samples),
           error_round_trip)
    report(error_bindings <= TOLERANCE, 'spatial_dynamics.dynamics (the library) = the node\'s inverse_dynamics (%d states)'
           % len(samples), error_bindings)
    return 0 if failures == 0 else 1


if __name__ == '__main__':
    try:
        sys.exit(main())
    except Exception as e:  # one FAIL line, whatever went wrong
        print('FAIL error: %s: %s' % (type(e).__name__, e))
        sys.exit(1)
