#!/usr/bin/env python3
"""Integration test of the Python client (spatial_dynamics.client) against the node on the Panda:
every wrapper, compared with the raw services called through rospy and with identities between
the services (FD(ID) = identity, M q'' + h = tau, wrench transforms on one body, a payload against
its weight as an external wrench)."""
import sys
import unittest
import xml.etree.ElementTree as ET

import numpy as np
import rospy
import rostest
from geometry_msgs.msg import Vector3, Wrench, WrenchStamped
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from spatial_dynamics.client import DynamicsClient, DynamicsError, JointValues, MassMatrixResult
from spatial_dynamics.srv import (ForwardDynamics, ForwardDynamicsRequest, InverseDynamics, InverseDynamicsRequest,
                                  InverseDynamicsTrajectory, InverseDynamicsTrajectoryRequest, MassMatrix,
                                  MassMatrixRequest, TransformWrench, TransformWrenchRequest)

PKG = 'spatial_dynamics'
NS = '/dynamics'
ARM = ['panda_joint%d' % k for k in range(1, 8)]


def raw_call(service, srv_type, request):
    rospy.wait_for_service(NS + '/' + service, 10.0)
    return rospy.ServiceProxy(NS + '/' + service, srv_type)(request)


def wrench_msg(frame, force, torque):
    msg = WrenchStamped()
    msg.header.frame_id = frame
    msg.wrench = Wrench(force=Vector3(*force), torque=Vector3(*torque))
    return msg


def relative_error(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.max(np.abs(a - b)) / max(1.0, np.max(np.abs(b)))


class PythonClient(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_python_client', anonymous=True)
        cls.client = DynamicsClient(NS)
        cls.client.wait_for_services(timeout=60.0)
        urdf = ET.fromstring(rospy.get_param('/robot_description'))
        cls.limits = {}
        for joint in urdf.findall('joint'):
            if joint.get('type') == 'fixed':
                continue
            limit = joint.find('limit')
            cls.limits[joint.get('name')] = (float(limit.get('lower')), float(limit.get('upper')),
                                             float(limit.get('effort')))
        cls.rng = np.random.default_rng(20261201)
        # One joint state, published continuously (the node refuses states older than max_state_age).
        cls.state_q = {name: cls.random_position(name) for name in cls.limits}
        cls.state_qd = {name: float(cls.rng.uniform(-0.5, 0.5)) for name in cls.limits}
        cls.publisher = rospy.Publisher('/joint_states', JointState, queue_size=10)
        cls.timer = rospy.Timer(rospy.Duration(0.02), cls.publish_state)
        deadline = rospy.get_time() + 30.0
        while True:
            try:
                cls.latest_torques = cls.client.inverse_dynamics()
                break
            except DynamicsError:
                if rospy.get_time() > deadline:
                    raise
                rospy.sleep(0.05)
        cls.names = cls.latest_torques.names
        cls.n = len(cls.names)

    @classmethod
    def tearDownClass(cls):
        cls.timer.shutdown()

    @classmethod
    def publish_state(cls, _event=None):
        msg = JointState()
        msg.header.stamp = rospy.Time.now()
        msg.name = list(cls.state_q)
        msg.position = [cls.state_q[name] for name in msg.name]
        msg.velocity = [cls.state_qd[name] for name in msg.name]
        cls.publisher.publish(msg)

    @classmethod
    def random_position(cls, name):
        lower, upper, _ = cls.limits[name]
        return float(cls.rng.uniform(lower + 0.1 * (upper - lower), upper - 0.1 * (upper - lower)))

    def random_q(self):
        return np.array([self.random_position(name) for name in self.names])

    def random_v(self, scale=1.0):
        return self.rng.uniform(-scale, scale, self.n)

    # --- inverse and forward dynamics, mass matrix ------------------------------------------

    def test_inverse_dynamics_equals_the_raw_service(self):
        q, qd, qdd = self.random_q(), self.random_v(), self.random_v(2.0)
        force, torque = (1.0, 2.0, -20.0), (0.1, 0.0, 0.3)
        tau = self.client.inverse_dynamics(q, qd, qdd, external_wrenches=[('panda_hand', force, torque)])
        raw = raw_call('inverse_dynamics', InverseDynamics, InverseDynamicsRequest(
            position=list(q), velocity=list(qd), acceleration=list(qdd),
            external_wrenches=[wrench_msg('panda_hand', force, torque)]))
        self.assertTrue(raw.success, raw.message)
        self.assertIsInstance(tau, JointValues)
        self.assertEqual(tau.names, list(raw.name))
        self.assertEqual(list(tau.keys()), list(raw.name))
        np.testing.assert_array_equal(tau.as_array(), np.array(raw.effort))
        self.assertEqual(tau['panda_joint4'], raw.effort[list(raw.name).index('panda_joint4')])
        self.assertEqual(tau.message, raw.message)
        # The wrench changes the answer (it is sent).
        without = self.client.inverse_dynamics(q, qd, qdd)
        self.assertGreater(np.max(np.abs(without.as_array() - tau.as_array())), 1e-3)
        # The node runs without an actuator model: no actuator effort, and rigid_body_only (sent)
        # gives the same answer.
        self.assertIsNone(tau.actuator_effort)
        rigid = self.client.inverse_dynamics(q, qd, qdd, rigid_body_only=True)
        np.testing.assert_array_equal(rigid.as_array(), without.as_array())

        # By name: the joints given, in the caller's order; the others from joint_states; an
        # acceleration mapping that leaves out a joint gives it 0.
        tau = self.client.inverse_dynamics(position={'panda_joint4': -1.2, 'panda_joint2': 0.3},
                                           acceleration={'panda_joint2': 1.0})
        raw = raw_call('inverse_dynamics', InverseDynamics, InverseDynamicsRequest(
            name=['panda_joint4', 'panda_joint2'], position=[-1.2, 0.3], acceleration=[0.0, 1.0]))
        self.assertTrue(raw.success, raw.message)
        self.assertEqual(tau.names, self.names)  # the answer is in the model's order
        np.testing.assert_array_equal(tau.as_array(), np.array(raw.effort))
        # ... and it is the full-length call with the joint state filled in.
        q_full = np.array([self.state_q[name] for name in self.names])
        q_full[self.names.index('panda_joint4')], q_full[self.names.index('panda_joint2')] = -1.2, 0.3
        qd_full = np.array([self.state_qd[name] for name in self.names])
        qdd_full = np.zeros(self.n)
        qdd_full[self.names.index('panda_joint2')] = 1.0
        full = self.client.inverse_dynamics(q_full, qd_full, qdd_full)
        self.assertLessEqual(relative_error(tau.as_array(), full.as_array()), 1e-12)

    def test_forward_dynamics_inverts_inverse_dynamics(self):
        wrenches = [('panda_hand', (3.0, -1.0, -15.0), (0.2, -0.1, 0.05)), {'frame': 'panda_link5', 'force': (0, 5, 0)}]
        worst = 0.0
        for _ in range(10):
            q, qd, qdd = self.random_q(), self.random_v(), self.random_v(3.0)
            tau = self.client.inverse_dynamics(q, qd, qdd, external_wrenches=wrenches)
            qdd_back = self.client.forward_dynamics(q, qd, tau.as_array(), external_wrenches=wrenches)
            self.assertEqual(qdd_back.names, self.names)
            worst = max(worst, relative_error(qdd_back.as_array(), qdd))
            # By name (mappings, e.g. the JointValues of an answer) gives the same.
            by_name = self.client.forward_dynamics(dict(zip(self.names, q)), dict(zip(self.names, qd)), tau,
                                                   external_wrenches=wrenches)
            np.testing.assert_array_equal(by_name.as_array(), qdd_back.as_array())
        self.assertLessEqual(worst, 1e-9)
        raw = raw_call('forward_dynamics', ForwardDynamics, ForwardDynamicsRequest(
            position=list(q), velocity=list(qd), effort=list(tau.as_array()),
            external_wrenches=[wrench_msg('panda_hand', (3.0, -1.0, -15.0), (0.2, -0.1, 0.05)),
                               wrench_msg('panda_link5', (0, 5, 0), (0, 0, 0))]))
        self.assertTrue(raw.success, raw.message)
        self.assertEqual(list(raw.name), qdd_back.names)
        np.testing.assert_array_equal(np.array(raw.acceleration), qdd_back.as_array())

    def test_mass_matrix_is_symmetric_and_matches_inverse_dynamics(self):
        zero = np.zeros(self.n)
        for _ in range(10):
            q, qdd = self.random_q(), self.random_v(3.0)
            m = self.client.mass_matrix(q)
            self.assertIsInstance(m, MassMatrixResult)
            self.assertEqual(m.names, self.names)
            self.assertEqual(m.matrix.shape, (self.n, self.n))
            scale = np.max(np.abs(m.matrix))
            self.assertLessEqual(np.max(np.abs(m.matrix - m.matrix.T)), 1e-12 * scale)
            np.linalg.cholesky(m.matrix)  # positive definite
            self.assertEqual(m.entry('panda_joint2', 'panda_joint4'),
                             m.matrix[self.names.index('panda_joint2'), self.names.index('panda_joint4')])
            h = self.client.inverse_dynamics(q, zero, zero).as_array()
            tau = self.client.inverse_dynamics(q, zero, qdd).as_array()
            self.assertLessEqual(relative_error(m.matrix @ qdd + h, tau), 1e-9)
        raw = raw_call('mass_matrix', MassMatrix, MassMatrixRequest(position=list(q)))
        self.assertTrue(raw.success, raw.message)
        np.testing.assert_array_equal(m.matrix.ravel(), np.array(raw.mass_matrix))
        # By name: the other joints at their joint_states position.
        part = self.client.mass_matrix({'panda_joint2': 0.4})
        q_full = np.array([self.state_q[name] for name in self.names])
        q_full[self.names.index('panda_joint2')] = 0.4
        np.testing.assert_array_equal(part.matrix, self.client.mass_matrix(q_full).matrix)

    # --- errors -------------------------------------------------------------------------------

    def test_node_errors_carry_the_node_message(self):
        with self.assertRaises(DynamicsError) as caught:
            self.client.inverse_dynamics(position={'panda_joint9': 0.1})
        raw = raw_call('inverse_dynamics', InverseDynamics,
                       InverseDynamicsRequest(name=['panda_joint9'], position=[0.1]))
        self.assertFalse(raw.success)
        self.assertIn("unknown joint 'panda_joint9'", raw.message)
        self.assertEqual(str(caught.exception), raw.message)
        self.assertEqual(caught.exception.node_message, raw.message)
        self.assertEqual(caught.exception.service, '/dynamics/inverse_dynamics')
        self.assertIsInstance(caught.exception, RuntimeError)

        with self.assertRaises(DynamicsError) as caught:
            self.client.forward_dynamics(effort=[1.0, 2.0])
        self.assertIn('effort has 2 entries but the model has %d joints' % self.n, str(caught.exception))
        self.assertEqual(caught.exception.service, '/dynamics/forward_dynamics')

        with self.assertRaises(DynamicsError) as caught:
            self.client.mass_matrix({'panda_joint9': 0.0})
        self.assertIn("unknown joint 'panda_joint9'", str(caught.exception))

        with self.assertRaises(DynamicsError) as caught:
            self.client.inverse_dynamics_trajectory([[0.0, 0.1]], [0.0], [[0.0, 0.0]], [[0.0, 0.0]],
                                                    joint_names=['panda_joint1', 'panda_joint1'])
        self.assertIn("'panda_joint1'", str(caught.exception))

    def test_failed_call_names_the_service(self):
        absent = DynamicsClient('/no_dynamics_here')
        with self.assertRaises(DynamicsError) as caught:
            absent.mass_matrix()
        self.assertIn('/no_dynamics_here/mass_matrix', str(caught.exception))
        self.assertEqual(caught.exception.service, '/no_dynamics_here/mass_matrix')
        self.assertIsNone(caught.exception.node_message)
        with self.assertRaises(DynamicsError) as caught:
            absent.wait_for_services(timeout=0.2)
        self.assertIn('/no_dynamics_here/', str(caught.exception))

    def test_argument_errors_are_raised_before_calling(self):
        with self.assertRaises(ValueError) as caught:  # mappings and sequences mixed
            self.client.inverse_dynamics(position={'panda_joint1': 0.0}, velocity=[0.0] * self.n)
        self.assertIn('position', str(caught.exception))
        with self.assertRaises(ValueError) as caught:  # velocity leaves out a joint position names
            self.client.inverse_dynamics(position={'panda_joint1': 0.0, 'panda_joint2': 0.1},
                                         velocity={'panda_joint1': 0.0})
        self.assertIn("velocity does not give joint 'panda_joint2'", str(caught.exception))
        with self.assertRaises(ValueError):
            self.client.inverse_dynamics(external_wrenches=[(1.0, 2.0)])
        with self.assertRaises(ValueError):
            self.client.transform_wrench(('panda_hand', (1.0, 2.0)), 'panda_link0')
        with self.assertRaises(ValueError):
            self.client.set_payload('panda_hand', 1.0, inertia=[[1, 2, 0], [0, 1, 0], [0, 0, 1]])
        with self.assertRaises(ValueError):
            self.client.inverse_dynamics_trajectory([[0.0] * self.n] * 2, time_from_start=[0.0])
        with self.assertRaises(ValueError):
            self.client.service_name('no_such_service')

    # --- trajectory -------------------------------------------------------------------------

    def test_trajectory_matches_inverse_dynamics(self):
        count = 5
        q = np.array([self.random_q() for _ in range(count)])
        qd = np.array([self.random_v() for _ in range(count)])
        qdd = np.array([self.random_v(2.0) for _ in range(count)])
        seven = self.names.index('panda_joint7')
        qd[:3], qdd[:3] = 0.0, 0.0  # still at the first three points: only gravity
        qdd[3, seven] = 5000.0      # a joint-7 acceleration beyond its 12 N m at point 3
        times = [0.0, 0.1, 0.2, 0.3, 0.4]
        result = self.client.inverse_dynamics_trajectory(q, times, qd, qdd)
        self.assertEqual(result.names, self.names)
        self.assertEqual(result.effort.shape, (count, self.n))
        np.testing.assert_array_equal(result.positions, q)
        np.testing.assert_array_equal(result.velocities, qd)
        np.testing.assert_array_equal(result.accelerations, qdd)
        np.testing.assert_allclose(result.time_from_start, times, rtol=0, atol=1e-9)
        for k in range(count):
            tau = self.client.inverse_dynamics(q[k], qd[k], qdd[k]).as_array()
            self.assertLessEqual(relative_error(result.effort[k], tau), 1e-9)
        np.testing.assert_array_equal(result.peak_effort.as_array(), np.max(np.abs(result.effort), axis=0))
        np.testing.assert_array_equal(result.effort_limit.as_array(), [self.limits[name][2] for name in self.names])
        for j, name in enumerate(self.names):
            over = np.nonzero(np.abs(result.effort[:, j]) > self.limits[name][2])[0]
            self.assertEqual(result.first_violation[name], int(over[0]) if over.size else -1, name)
        self.assertEqual(result.first_violation['panda_joint7'], 3)
        self.assertEqual(result.violations()['panda_joint7'], 3)
        self.assertNotIn('panda_joint1', result.violations())

        raw = raw_call('inverse_dynamics_trajectory', InverseDynamicsTrajectory,
                       InverseDynamicsTrajectoryRequest(trajectory=JointTrajectory(points=[
                           JointTrajectoryPoint(positions=list(q[k]), velocities=list(qd[k]),
                                                accelerations=list(qdd[k]),
                                                time_from_start=rospy.Duration.from_sec(times[k]))
                           for k in range(count)])))
        self.assertTrue(raw.success, raw.message)
        np.testing.assert_array_equal(np.array([p.effort for p in raw.points]), result.effort)
        np.testing.assert_array_equal(np.array(raw.first_violation), result.first_violation.as_array())

    def test_trajectory_by_name_with_differences(self):
        names = ['panda_joint4', 'panda_joint2']
        positions = [[-1.5, 0.0], [-1.4, 0.1], [-1.2, 0.3]]
        result = self.client.inverse_dynamics_trajectory(positions, [0.0, 0.5, 1.0], joint_names=names)
        self.assertEqual(result.names, self.names)
        self.assertTrue(result.message, 'the node says which points got differences')
        j4, j2 = self.names.index('panda_joint4'), self.names.index('panda_joint2')
        # Central differences at the middle point; the unnamed joints stay still at their joint state.
        self.assertAlmostEqual(result.velocities[1, j4], (-1.2 + 1.5) / 1.0, delta=1e-12)
        self.assertAlmostEqual(result.velocities[1, j2], 0.3 / 1.0, delta=1e-12)
        self.assertAlmostEqual(result.accelerations[1, j2], (0.3 - 2 * 0.1 + 0.0) / 0.25, delta=1e-9)
        j1 = self.names.index('panda_joint1')
        np.testing.assert_array_equal(result.positions[:, j1], [self.state_q['panda_joint1']] * 3)
        np.testing.assert_array_equal(result.velocities[:, j1], [0.0] * 3)
        # The middle point equals inverse dynamics with the same state.
        tau = self.client.inverse_dynamics(result.positions[1], result.velocities[1], result.accelerations[1])
        self.assertLessEqual(relative_error(result.effort[1], tau.as_array()), 1e-9)
        # A JointTrajectory message is sent as it is, and gives the same.
        msg = JointTrajectory(joint_names=names, points=[
            JointTrajectoryPoint(positions=p, time_from_start=rospy.Duration.from_sec(t))
            for p, t in zip(positions, [0.0, 0.5, 1.0])])
        again = self.client.inverse_dynamics_trajectory(msg)
        np.testing.assert_array_equal(again.effort, result.effort)
        self.assertEqual(again.message, result.message)

    # --- wrenches and payloads --------------------------------------------------------------

    def test_transform_wrench_round_trip(self):
        q = self.random_q()
        force, torque = np.array([1.0, -2.0, -10.0]), np.array([0.3, 0.2, -0.1])
        there = self.client.transform_wrench(('panda_hand', force, torque), 'panda_link0', position=q)
        self.assertEqual(there.frame, 'panda_link0')
        self.assertAlmostEqual(np.linalg.norm(there.force), np.linalg.norm(force), delta=1e-12)
        self.assertGreater(np.max(np.abs(there.torque - torque)), 1e-3)  # r x f and the rotation
        raw = raw_call('transform_wrench', TransformWrench, TransformWrenchRequest(
            wrench=wrench_msg('panda_hand', force, torque), target_frame='panda_link0', position=list(q)))
        self.assertTrue(raw.success, raw.message)
        np.testing.assert_array_equal(there.force, [raw.wrench.wrench.force.x, raw.wrench.wrench.force.y,
                                                    raw.wrench.wrench.force.z])
        np.testing.assert_array_equal(there.torque, [raw.wrench.wrench.torque.x, raw.wrench.wrench.torque.y,
                                                     raw.wrench.wrench.torque.z])
        back = self.client.transform_wrench(there, 'panda_hand', position=q)
        self.assertLessEqual(np.max(np.abs(back.force - force)), 1e-9)
        self.assertLessEqual(np.max(np.abs(back.torque - torque)), 1e-9)
        np.testing.assert_array_equal(back.as_array()[:3], back.force)
        # panda_link8 is on the same body as panda_hand: the wrench moved there acts the same.
        on_link8 = self.client.transform_wrench(('panda_hand', force, torque), 'panda_link8', position=q)
        qd, qdd = self.random_v(), self.random_v()
        tau_hand = self.client.inverse_dynamics(q, qd, qdd, external_wrenches=[('panda_hand', force, torque)])
        tau_link8 = self.client.inverse_dynamics(q, qd, qdd, external_wrenches=[on_link8])
        self.assertLessEqual(relative_error(tau_link8.as_array(), tau_hand.as_array()), 1e-9)
        # By name: the latest joint state for the others.
        part = self.client.transform_wrench(('panda_hand', force, torque), 'panda_link0', {'panda_joint1': 0.2})
        q_full = np.array([self.state_q[name] for name in self.names])
        q_full[self.names.index('panda_joint1')] = 0.2
        full = self.client.transform_wrench(('panda_hand', force, torque), 'panda_link0', q_full)
        np.testing.assert_array_equal(part.as_array(), full.as_array())
        with self.assertRaises(DynamicsError) as caught:
            self.client.transform_wrench(('panda_hand', force, torque), 'no_such_frame', position=q)
        raw = raw_call('transform_wrench', TransformWrench, TransformWrenchRequest(
            wrench=wrench_msg('panda_hand', force, torque), target_frame='no_such_frame', position=list(q)))
        self.assertFalse(raw.success)
        self.assertEqual(str(caught.exception), raw.message)

    def test_payload_round_trip(self):
        q, zero = self.random_q(), np.zeros(self.n)
        mass, com = 2.0, np.array([0.01, -0.02, 0.1])
        inertia = np.array([[0.004, 0.0001, 0.0], [0.0001, 0.005, 0.0002], [0.0, 0.0002, 0.002]])
        base = self.client.inverse_dynamics(q, zero, zero).as_array()
        base_m = self.client.mass_matrix(q).matrix
        # The payload's weight as an external wrench on panda_hand, about the frame's origin.
        weight = self.client.transform_wrench(('panda_link0', (0.0, 0.0, -9.81 * mass)), 'panda_hand', q).force
        expected = self.client.inverse_dynamics(q, zero, zero,
                                                external_wrenches=[('panda_hand', weight, np.cross(com, weight))])
        try:
            message = self.client.set_payload('panda_hand', mass, com, inertia)
            self.assertIn("attached to 'panda_hand'", message)
            loaded = self.client.inverse_dynamics(q, zero, zero).as_array()
            self.assertGreater(np.max(np.abs(loaded - base)), 0.1)
            self.assertLessEqual(relative_error(loaded, expected.as_array()), 1e-9)
            loaded_m = self.client.mass_matrix(q).matrix
            extra = loaded_m - base_m
            self.assertGreater(np.trace(extra), 0.01)
            self.assertGreaterEqual(np.min(np.linalg.eigvalsh(extra)), -1e-9)
            # The same inertia as its six numbers replaces the payload with an identical one.
            self.client.set_payload('panda_hand', mass, com, (0.004, 0.0001, 0.0, 0.005, 0.0002, 0.002))
            np.testing.assert_array_equal(self.client.mass_matrix(q).matrix, loaded_m)
        finally:
            message = self.client.clear_payload('panda_hand')
        self.assertEqual(message, "payload removed from 'panda_hand'")
        self.assertLessEqual(relative_error(self.client.inverse_dynamics(q, zero, zero).as_array(), base), 1e-12)
        self.assertLessEqual(relative_error(self.client.mass_matrix(q).matrix, base_m), 1e-12)
        self.assertEqual(self.client.clear_payload('panda_hand'), "no payload on 'panda_hand' to remove")
        with self.assertRaises(DynamicsError) as caught:
            self.client.set_payload('no_such_frame', 1.0)
        self.assertEqual(str(caught.exception), "unknown frame 'no_such_frame' (not a link of the robot model)")
        self.assertEqual(caught.exception.service, '/dynamics/set_payload')

    # --- scenes and reload ------------------------------------------------------------------

    def test_scene_client(self):
        arm = DynamicsClient(NS, scene='arm')
        self.assertEqual(arm.service_name('inverse_dynamics'), '/dynamics/arm/inverse_dynamics')
        self.assertEqual(arm.service_name('mass_matrix'), '/dynamics/arm/mass_matrix')
        self.assertEqual(arm.service_name('set_payload'), '/dynamics/set_payload')
        arm.wait_for_services(timeout=10.0)
        index = [self.names.index(name) for name in ARM]
        q, qd, qdd = self.random_q(), self.random_v(), self.random_v(2.0)
        fingers = [k for k in range(self.n) if k not in index]
        q[fingers] = [self.state_q[self.names[k]] for k in fingers]  # where the scene locks them
        qd[fingers], qdd[fingers] = 0.0, 0.0
        tau_arm = arm.inverse_dynamics(q[index], qd[index], qdd[index])
        self.assertEqual(tau_arm.names, ARM)
        tau = self.client.inverse_dynamics(q, qd, qdd).as_array()
        self.assertLessEqual(relative_error(tau_arm.as_array(), tau[index]), 1e-9)
        m_arm = arm.mass_matrix(q[index])
        self.assertEqual(m_arm.names, ARM)
        self.assertLessEqual(relative_error(m_arm.matrix, self.client.mass_matrix(q).matrix[np.ix_(index, index)]),
                             1e-9)
        qdd_arm = arm.forward_dynamics(q[index], qd[index], tau_arm.as_array())
        self.assertLessEqual(relative_error(qdd_arm.as_array(), qdd[index]), 1e-9)

    def test_payload_identification_round_trip(self):
        # efforts of the arm carrying a tool, computed by the node itself; then identified from them
        arm = ['panda_joint%d' % k for k in range(1, 8)]
        motion = self.client.excitation_trajectory(arm, 10.0, speed_scale=0.4)
        self.assertEqual(motion.names, arm)
        self.assertEqual(motion.positions.shape, (1001, 7))
        self.assertLess(np.abs(motion.velocities[[0, -1]]).max(), 1e-12)
        # the fingers where joint_states has them, at rest, named (joints left out would take their velocity)
        fingers = [name for name in self.names if name not in arm]
        samples = motion.trajectory
        samples.joint_names = arm + fingers
        for point in samples.points:
            point.positions = list(point.positions) + [self.state_q[name] for name in fingers]
            point.velocities = list(point.velocities) + [0.0] * len(fingers)
            point.accelerations = list(point.accelerations) + [0.0] * len(fingers)
        com, inertia = (0.01, -0.02, 0.08), np.diag([0.02, 0.03, 0.04])
        self.client.set_payload('panda_link8', 1.7, com, inertia)
        try:
            loaded = self.client.inverse_dynamics_trajectory(samples)
        finally:
            self.client.clear_payload('panda_link8')
        for point, effort in zip(samples.points, loaded.effort):
            point.effort = [float(effort[loaded.names.index(name)]) for name in samples.joint_names]
        result = self.client.identify_payload('panda_link8', samples)
        self.assertAlmostEqual(result.mass, 1.7, places=6)
        np.testing.assert_allclose(result.center_of_mass, com, atol=1e-7)
        np.testing.assert_allclose(result.inertia, inertia, atol=1e-7)
        self.assertEqual(result.unidentifiable, [])
        self.assertEqual(list(result.residual_rms.keys()), arm + fingers)
        self.assertIsNone(result.damping)
        with self.assertRaises(DynamicsError) as caught:
            self.client.identify_payload('no_such_frame', samples)
        self.assertIn("'no_such_frame'", str(caught.exception))
        with self.assertRaises(DynamicsError):
            self.client.excitation_trajectory(arm, 10.0, speed_scale=2.0)

    def test_reload(self):
        q, qd, qdd = self.random_q(), self.random_v(), self.random_v()
        before = self.client.inverse_dynamics(q, qd, qdd).as_array()
        message = self.client.reload()
        self.assertIsInstance(message, str)
        np.testing.assert_array_equal(self.client.inverse_dynamics(q, qd, qdd).as_array(), before)


    def test_zz_floating_base(self):
        """A floating Panda (~root_joint floating, reloaded): the base and contact fields in and out.
        Runs last: it reloads the robot twice."""
        rospy.set_param(NS + '/root_joint', 'floating')
        try:
            self.client.reload()
            q, qd, tau = self.random_q(), self.random_v(), self.random_v(5.0)
            pose = ((0.1, -0.2, 0.3), (0.0, 0.0, np.sin(0.2), np.cos(0.2)))
            twist = [0.1, -0.2, 0.3, 0.0, 0.1, -0.1]
            hand = [('panda_hand', 'surface', 0.5)]
            # FD with the hand held, then ID of its accelerations: the same joint torques and wrench.
            fd = self.client.forward_dynamics(q, qd, tau, base_pose=pose, base_twist=twist, contacts=hand)
            self.assertEqual(len(fd.base_acceleration), 6)
            self.assertEqual([w.frame for w in fd.contact_wrenches], ['panda_hand'])
            inv = self.client.inverse_dynamics(q, qd, fd.as_array(), base_pose=pose, base_twist=twist,
                                               base_acceleration=fd.base_acceleration, contacts=hand)
            self.assertLess(relative_error(inv.as_array(), tau), 1e-9)
            self.assertLess(relative_error(inv.contact_wrenches[0].as_array(), fd.contact_wrenches[0].as_array()), 1e-9)
            self.assertLess(np.max(np.abs(inv.base_wrench.as_array())), 1e-9)
            # Without contacts the base wrench is what the motion needs; the mass matrix covers the base.
            free = self.client.inverse_dynamics(q, qd, fd.as_array(), base_pose=pose, base_twist=twist,
                                                base_acceleration=fd.base_acceleration, ignore_contacts=True)
            self.assertEqual(free.contact_wrenches, [])
            self.assertGreater(np.linalg.norm(free.base_wrench.as_array()), 1.0)
            m = self.client.mass_matrix(q, base_pose=pose)
            self.assertEqual(m.names[:6], ['root_joint/%s' % c for c in ('wx', 'wy', 'wz', 'vx', 'vy', 'vz')])
            self.assertEqual(m.matrix.shape, (self.n + 6, self.n + 6))
            # The node's contacts, set by name; a bad one refused naming it.
            self.assertIn('panda_hand', self.client.set_contacts([{'frame': 'panda_hand', 'kind': 'point'}]))
            held = self.client.inverse_dynamics(q, qd, base_pose=pose)
            self.assertEqual([w.frame for w in held.contact_wrenches], ['panda_hand'])
            with self.assertRaises(DynamicsError) as caught:
                self.client.set_contacts([('no_such_frame', 'point')])
            self.assertIn("'no_such_frame'", str(caught.exception))
            with self.assertRaises(DynamicsError) as caught:
                self.client.inverse_dynamics(q, qd, base_pose=((0, 0, 0), (0, 0, 0, 2.0)))
            self.assertIn('base_pose.orientation', str(caught.exception))
            self.client.set_contacts([])
        finally:
            rospy.set_param(NS + '/root_joint', 'fixed')
            self.client.reload()
        with self.assertRaises(DynamicsError) as caught:
            self.client.inverse_dynamics(base_pose=((0, 0, 0), (0, 0, 0, 1)))
        self.assertIn('base_pose', str(caught.exception))


if __name__ == '__main__':
    rostest.rosrun(PKG, 'node_python_client', PythonClient, sys.argv)
