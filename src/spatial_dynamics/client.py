"""A Python client of the dynamics node's services (README, "The node").

    from spatial_dynamics.client import DynamicsClient
    c = DynamicsClient('/dynamics')
    tau = c.inverse_dynamics(position={'panda_joint2': 0.3}, acceleration={'panda_joint4': 1.0})
    tau['panda_joint2'], tau.as_array()

Joint inputs (position, velocity, acceleration, effort) are each one of
  - None: left out; the node takes the latest joint_states (position, velocity) or zero
    (acceleration, effort);
  - a mapping joint name -> value: only these joints. A request has one `name` list for all its
    arrays, so the mappings of one call are merged: a joint named in one mapping but missing from
    an acceleration or effort mapping gets 0 there (the node's default); missing from a position or
    velocity mapping it is an error (ValueError), since the node could only take the latest
    joint_states for all joints of that array or for none;
  - a sequence (list, tuple, numpy array) in the model's joint order, full length.
Mappings and sequences cannot be mixed in one call (ValueError).

A floating base (~root_joint floating) takes base_pose (a geometry_msgs/Pose, or (position xyz,
quaternion xyzw)), base_twist and base_acceleration (a Twist/Accel message, or six numbers
(wx wy wz vx vy vz) in the root link's axes); left out, the node takes its base state (odometry or
tf). contacts=[(frame, kind[, friction]) or {frame, kind, friction}] replaces the node's contacts
for one call; ignore_contacts=True uses none. The answers then carry `contact_wrenches` (WrenchResult
per contact, in its frame), `base_wrench` (WrenchResult in the root link's axes), `contact_violations`
and, from forward_dynamics, `base_acceleration` (six numbers, angular first).

Answers keep the node's joint order (the response's `name`). A `success: false` answer raises
DynamicsError with the node's message verbatim; a failed call (no such service, node gone) raises
DynamicsError naming the service. A successful answer's `message` (warnings: a position outside its
limits, a joint state without velocities, ...) is kept in the result's `message`.
"""
import collections
import collections.abc

import genpy
import numpy as np
import rosgraph.names
import rospy
from geometry_msgs.msg import Accel, Inertia, Point, Pose, Quaternion, Twist, Vector3, Wrench, WrenchStamped
from std_srvs.srv import Trigger, TriggerRequest
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from spatial_dynamics.srv import (ExcitationTrajectory, ExcitationTrajectoryRequest, ForwardDynamics,
                                  ForwardDynamicsRequest, IdentifyPayload, IdentifyPayloadRequest, InverseDynamics,
                                  InverseDynamicsRequest, InverseDynamicsTrajectory, InverseDynamicsTrajectoryRequest, MassMatrix,
                                  MassMatrixRequest, SetContacts, SetContactsRequest, SetPayload, SetPayloadRequest,
                                  TransformWrench, TransformWrenchRequest)

__all__ = ['DynamicsClient', 'DynamicsError', 'ExcitationResult', 'JointValues', 'MassMatrixResult', 'PayloadResult',
           'TrajectoryResult', 'WrenchResult']


class DynamicsError(RuntimeError):
    """A service answered `success: false` (str(error) is the node's message, verbatim), or the call
    itself failed (the message names the service). `service` is the service's resolved name;
    `node_message` the node's message, or None when there was no answer."""

    def __init__(self, message, service=None, node_message=None):
        super().__init__(message)
        self.service = service
        self.node_message = node_message


class JointValues(collections.OrderedDict):
    """Joint name -> value, in the model's joint order (the response's `name`)."""

    def __init__(self, names=(), values=(), message=''):
        names, values = list(names), list(values)
        if len(names) != len(values):
            raise DynamicsError('the answer has %d names but %d values' % (len(names), len(values)))
        super().__init__(zip(names, values))
        self.message = message

    @property
    def names(self):
        return list(self.keys())

    def as_array(self):
        """The values as a numpy array, in the model's joint order."""
        return np.array(list(self.values()), dtype=float)

    def __reduce__(self):
        return (self.__class__, (self.names, list(self.values()), self.message))


class MassMatrixResult(object):
    """M(q): `matrix` (n x n numpy array) with rows and columns in the order of `names`."""

    def __init__(self, names, matrix, message=''):
        self.names = list(names)
        self.matrix = matrix
        self.message = message

    def as_array(self):
        return self.matrix

    def entry(self, row, column):
        """M[row, column] by joint names."""
        return self.matrix[self.names.index(row), self.names.index(column)]

    def __repr__(self):
        return 'MassMatrixResult(names=%r, matrix=%r)' % (self.names, self.matrix)


class WrenchResult(object):
    """A wrench expressed in `frame` about its origin: `force`, `torque` (numpy 3-vectors), `stamp`."""

    def __init__(self, frame, force, torque, stamp=None, message=''):
        self.frame = frame
        self.force = np.asarray(force, dtype=float)
        self.torque = np.asarray(torque, dtype=float)
        self.stamp = stamp if stamp is not None else rospy.Time()
        self.message = message

    def as_array(self):
        """[fx, fy, fz, tx, ty, tz]."""
        return np.concatenate([self.force, self.torque])

    def to_msg(self):
        return _wrench_stamped(self.frame, self.force, self.torque, self.stamp)

    def __repr__(self):
        return 'WrenchResult(frame=%r, force=%r, torque=%r)' % (self.frame, self.force, self.torque)


class TrajectoryResult(object):
    """Inverse dynamics along a trajectory: `names` (the model's joint order); per point (rows)
    `time_from_start` (seconds), `positions`, `velocities`, `accelerations`, `effort` as
    (points x joints) numpy arrays; per joint `peak_effort`, `effort_limit` (inf: no limit) and
    `first_violation` (first point with |effort| > limit, -1 if none) as JointValues; `points`
    the response's JointTrajectoryPoints."""

    def __init__(self, response):
        self.names = list(response.name)
        self.message = response.message
        self.points = list(response.points)
        n = len(self.names)

        def rows(field):
            return np.array([list(getattr(p, field)) for p in self.points], dtype=float).reshape(len(self.points), n)

        self.time_from_start = np.array([p.time_from_start.to_sec() for p in self.points], dtype=float)
        self.positions = rows('positions')
        self.velocities = rows('velocities')
        self.accelerations = rows('accelerations')
        self.effort = rows('effort')
        self.peak_effort = JointValues(self.names, response.peak_effort)
        self.effort_limit = JointValues(self.names, response.effort_limit)
        self.first_violation = JointValues(self.names, [int(k) for k in response.first_violation])

    def violations(self):
        """Joint name -> first violating point, for the joints that exceed their limit."""
        return collections.OrderedDict((name, k) for name, k in self.first_violation.items() if k >= 0)


class ExcitationResult(object):
    """An excitation trajectory: `names`; per point (rows) `time_from_start` (seconds), `positions`,
    `velocities`, `accelerations` as (points x joints) numpy arrays; `condition_number`; `trajectory`
    the trajectory_msgs/JointTrajectory to hand to a controller."""

    def __init__(self, response):
        self.trajectory = response.trajectory
        self.names = list(response.trajectory.joint_names)
        self.condition_number = response.condition_number
        self.message = response.message
        points = response.trajectory.points
        self.time_from_start = np.array([p.time_from_start.to_sec() for p in points])
        for field in ('positions', 'velocities', 'accelerations'):
            setattr(self, field, np.array([list(getattr(p, field)) for p in points], dtype=float).reshape(len(points), len(self.names)))


class PayloadResult(object):
    """An identified payload: `mass` [kg], `center_of_mass` [m] in the frame, `inertia` [kg m^2] about
    the centre of mass in the frame's axes (3x3), the same with `_stddev` (NaN where a parameter held
    at the prior enters), `unidentifiable` (the held parameters), `residual_rms` (JointValues, per
    joint whose efforts were used), `condition_number`, and with identify_friction `damping` and
    `friction` (JointValues; else None)."""

    def __init__(self, response):
        def fields(m):
            inertia = np.array([[m.ixx, m.ixy, m.ixz], [m.ixy, m.iyy, m.iyz], [m.ixz, m.iyz, m.izz]])
            return m.m, np.array([m.com.x, m.com.y, m.com.z]), inertia
        self.mass, self.center_of_mass, self.inertia = fields(response.inertia)
        self.mass_stddev, self.center_of_mass_stddev, self.inertia_stddev = fields(response.stddev)
        self.unidentifiable = list(response.unidentifiable)
        self.residual_rms = JointValues(response.name, response.residual_rms)
        self.condition_number = response.condition_number
        self.damping = JointValues(response.name, response.damping) if response.damping else None
        self.friction = JointValues(response.name, response.friction) if response.friction else None
        self.message = response.message


def _is_mapping(value):
    return isinstance(value, collections.abc.Mapping)


def _joint_arrays(fields):
    """fields: [(field name, value, zero default?)] -> (names, [float lists]) for one request."""
    given = [(field, value, zero) for field, value, zero in fields if value is not None]
    mappings = [field for field, value, _ in given if _is_mapping(value)]
    if not mappings:
        return [], [[] if value is None else [float(x) for x in np.asarray(value, dtype=float).ravel()]
                    for _, value, _ in fields]
    if len(mappings) != len(given):
        sequences = [field for field, value, _ in given if not _is_mapping(value)]
        raise ValueError('%s given by joint name but %s in the model\'s order; give all of them one way'
                         % (', '.join(mappings), ', '.join(sequences)))
    names = []
    for _, value, _ in given:
        for name in value:
            if name not in names:
                names.append(name)
    arrays = []
    for field, value, zero in fields:
        if value is None or (not value and not zero):
            arrays.append([])
            continue
        missing = [name for name in names if name not in value]
        if missing and not zero:
            raise ValueError("%s does not give joint '%s', which the call names elsewhere; a request has one name "
                             "list for all its arrays, so give %s for every named joint or for none (then it is "
                             "the latest joint_states)" % (field, missing[0], field))
        arrays.append([float(value.get(name, 0.0)) for name in names])
    return names, arrays


def _vector3(values, what):
    v = np.asarray(values, dtype=float).ravel()
    if v.shape != (3,):
        raise ValueError('%s must have 3 entries, not %d' % (what, v.size))
    return v


def _wrench_stamped(frame, force=(0.0, 0.0, 0.0), torque=(0.0, 0.0, 0.0), stamp=None):
    f, t = _vector3(force, 'force'), _vector3(torque, 'torque')
    msg = WrenchStamped()
    msg.header.frame_id = frame
    if stamp is not None:
        msg.header.stamp = stamp
    msg.wrench = Wrench(force=Vector3(*f), torque=Vector3(*t))
    return msg


def _to_wrench_stamped(wrench):
    """A WrenchStamped, a WrenchResult, (frame, force) or (frame, force, torque), or a mapping with
    'frame', 'force' and optionally 'torque' and 'stamp'."""
    if isinstance(wrench, WrenchStamped):
        return wrench
    if isinstance(wrench, WrenchResult):
        return wrench.to_msg()
    if _is_mapping(wrench):
        return _wrench_stamped(wrench['frame'], wrench.get('force', (0.0, 0.0, 0.0)),
                               wrench.get('torque', (0.0, 0.0, 0.0)), wrench.get('stamp'))
    if isinstance(wrench, (tuple, list)) and len(wrench) in (2, 3) and isinstance(wrench[0], str):
        return _wrench_stamped(*wrench)
    raise ValueError('a wrench is a geometry_msgs/WrenchStamped, a WrenchResult, (frame, force[, torque]) or '
                     '{frame, force, torque}; got %r' % (wrench,))


def _pose(pose):
    """A geometry_msgs/Pose, or (position xyz, quaternion xyzw)."""
    if isinstance(pose, Pose):
        return pose
    position, orientation = pose
    p = _vector3(position, 'base_pose position')
    o = np.asarray(orientation, dtype=float).ravel()
    if o.shape != (4,):
        raise ValueError('base_pose orientation must be a quaternion (x, y, z, w), not %d numbers' % o.size)
    return Pose(position=Point(*p), orientation=Quaternion(*o))


def _six(value, message_type, what):
    """A Twist or Accel message, or six numbers (angular xyz, linear xyz)."""
    if isinstance(value, message_type):
        return value
    v = np.asarray(value, dtype=float).ravel()
    if v.shape != (6,):
        raise ValueError('%s must be a %s or six numbers (wx wy wz vx vy vz), not %d' % (what, message_type.__name__, v.size))
    return message_type(angular=Vector3(*v[:3]), linear=Vector3(*v[3:]))


def _contact_lists(contacts):
    """[(frame, kind[, friction])] or [{frame, kind, friction}] -> (frames, kinds, frictions)."""
    frames, kinds, frictions = [], [], []
    for contact in contacts:
        if _is_mapping(contact):
            frame, kind, friction = contact['frame'], contact['kind'], contact.get('friction')
        else:
            frame, kind, friction = (tuple(contact) + (None,))[:3]
        frames.append(str(frame))
        kinds.append(str(kind))
        frictions.append(friction)
    if all(f is None for f in frictions):
        return frames, kinds, []
    return frames, kinds, [0.0 if f is None else float(f) for f in frictions]


def _set_base_and_contacts(request, base_pose, base_twist, contacts, ignore_contacts):
    if base_pose is not None:
        request.base_pose = _pose(base_pose)
    if base_twist is not None:
        request.base_twist = _six(base_twist, Twist, 'base_twist')
    if contacts is not None:
        request.contact_frames, request.contact_kinds, request.contact_frictions = _contact_lists(contacts)
    request.ignore_contacts = bool(ignore_contacts)


def _with_contact_answers(result, response):
    def result_of(w):
        return WrenchResult(w.header.frame_id, (w.wrench.force.x, w.wrench.force.y, w.wrench.force.z),
                            (w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z), w.header.stamp)
    result.contact_wrenches = [result_of(w) for w in response.contact_wrenches]
    b = response.base_wrench
    result.base_wrench = WrenchResult('', (b.force.x, b.force.y, b.force.z), (b.torque.x, b.torque.y, b.torque.z))
    result.contact_violations = list(response.contact_violations)
    return result


def _duration(t):
    return t if isinstance(t, genpy.Duration) else rospy.Duration.from_sec(float(t))


def _inertia_upper(inertia):
    """(ixx, ixy, ixz, iyy, iyz, izz) from a 3x3 symmetric matrix or those 6 numbers."""
    a = np.asarray(inertia, dtype=float)
    if a.shape == (3, 3):
        if not np.allclose(a, a.T, rtol=1e-12, atol=0.0):
            raise ValueError('the payload inertia matrix is not symmetric')
        return a[0, 0], a[0, 1], a[0, 2], a[1, 1], a[1, 2], a[2, 2]
    if a.shape == (6,):
        return tuple(a)
    raise ValueError('the payload inertia is a 3x3 matrix or (ixx, ixy, ixz, iyy, iyz, izz), not shape %s'
                     % (a.shape,))


class DynamicsClient(object):
    """Calls the services of the dynamics node at `namespace` (the node's private namespace, e.g.
    '/dynamics'; relative names resolve as in rospy). With `scene`, the joint services
    (inverse_dynamics, inverse_dynamics_trajectory, forward_dynamics, mass_matrix) are the scene's
    (`<namespace>/<scene>/...`); transform_wrench, set_payload and reload are the node's."""

    _SCENE_SERVICES = ('inverse_dynamics', 'inverse_dynamics_trajectory', 'forward_dynamics', 'mass_matrix')
    _TYPES = {
        'inverse_dynamics': InverseDynamics,
        'inverse_dynamics_trajectory': InverseDynamicsTrajectory,
        'forward_dynamics': ForwardDynamics,
        'mass_matrix': MassMatrix,
        'transform_wrench': TransformWrench,
        'set_payload': SetPayload,
        'set_contacts': SetContacts,
        'reload': Trigger,
        'excitation_trajectory': ExcitationTrajectory,
        'identify_payload': IdentifyPayload,
    }

    def __init__(self, namespace='/dynamics', scene=None, persistent=False):
        self.namespace = rospy.resolve_name(namespace)
        self.scene = scene
        self._persistent = persistent
        self._proxies = {}

    def service_name(self, service):
        """The resolved name of one of the node's services, e.g. '/dynamics/inverse_dynamics'."""
        if service not in self._TYPES:
            raise ValueError('the node has no service %r' % (service,))
        if self.scene and service in self._SCENE_SERVICES:
            return rosgraph.names.ns_join(rosgraph.names.ns_join(self.namespace, self.scene), service)
        return rosgraph.names.ns_join(self.namespace, service)

    def wait_for_services(self, timeout=None):
        """Waits until every service of this client is advertised; raises DynamicsError after
        `timeout` seconds (None: forever)."""
        for service in self._TYPES:
            name = self.service_name(service)
            try:
                rospy.wait_for_service(name, timeout)
            except rospy.ROSException as error:
                raise DynamicsError('service %s did not appear: %s' % (name, error), service=name)

    def close(self):
        for proxy in self._proxies.values():
            proxy.close()
        self._proxies.clear()

    def _call(self, service, request):
        name = self.service_name(service)
        proxy = self._proxies.get(service)
        if proxy is None:
            proxy = rospy.ServiceProxy(name, self._TYPES[service], persistent=self._persistent)
            self._proxies[service] = proxy
        try:
            response = proxy.call(request)
        except rospy.ServiceException as error:
            if self._persistent:
                self._proxies.pop(service, None)
            raise DynamicsError('call to service %s failed: %s' % (name, error), service=name)
        if not response.success:
            raise DynamicsError(response.message, service=name, node_message=response.message)
        return response

    # --- joint services ---------------------------------------------------------------------

    def inverse_dynamics(self, position=None, velocity=None, acceleration=None, external_wrenches=(),
                         rigid_body_only=False, base_pose=None, base_twist=None, base_acceleration=None,
                         contacts=None, ignore_contacts=False):
        """tau = ID(q, qd, qdd, wrenches), as JointValues of the efforts, with the actuator terms of
        the node's ~actuator_model unless rigid_body_only. Its `actuator_effort` is the actuators'
        part of the efforts (JointValues), or None when the answer has none; a floating base's
        `contact_wrenches`, `base_wrench` and `contact_violations` as in the module's text."""
        request = InverseDynamicsRequest()
        request.name, (request.position, request.velocity, request.acceleration) = _joint_arrays(
            [('position', position, False), ('velocity', velocity, False), ('acceleration', acceleration, True)])
        request.external_wrenches = [_to_wrench_stamped(w) for w in external_wrenches or ()]
        request.rigid_body_only = bool(rigid_body_only)
        _set_base_and_contacts(request, base_pose, base_twist, contacts, ignore_contacts)
        if base_acceleration is not None:
            request.base_acceleration = _six(base_acceleration, Accel, 'base_acceleration')
        response = self._call('inverse_dynamics', request)
        result = JointValues(response.name, response.effort, response.message)
        result.actuator_effort = (JointValues(response.name, response.actuator_effort)
                                  if response.actuator_effort else None)
        return _with_contact_answers(result, response)

    def forward_dynamics(self, position=None, velocity=None, effort=None, external_wrenches=(),
                         rigid_body_only=False, base_pose=None, base_twist=None, contacts=None, ignore_contacts=False):
        """qdd = FD(q, qd, tau, wrenches), as JointValues of the accelerations (actuator terms as
        for inverse_dynamics); a floating base's `base_acceleration` and contact answers as in the
        module's text."""
        request = ForwardDynamicsRequest()
        request.name, (request.position, request.velocity, request.effort) = _joint_arrays(
            [('position', position, False), ('velocity', velocity, False), ('effort', effort, True)])
        request.external_wrenches = [_to_wrench_stamped(w) for w in external_wrenches or ()]
        request.rigid_body_only = bool(rigid_body_only)
        _set_base_and_contacts(request, base_pose, base_twist, contacts, ignore_contacts)
        response = self._call('forward_dynamics', request)
        result = _with_contact_answers(JointValues(response.name, response.acceleration, response.message), response)
        a = response.base_acceleration
        result.base_acceleration = np.array([a.angular.x, a.angular.y, a.angular.z, a.linear.x, a.linear.y, a.linear.z])
        return result

    def mass_matrix(self, position=None, rigid_body_only=False, base_pose=None):
        """M(q) (+ diag(armature) with an actuator model, unless rigid_body_only) as a
        MassMatrixResult (`matrix`, `names`); a floating base's six coordinates first."""
        request = MassMatrixRequest()
        request.name, (request.position,) = _joint_arrays([('position', position, False)])
        request.rigid_body_only = bool(rigid_body_only)
        if base_pose is not None:
            request.base_pose = _pose(base_pose)
        response = self._call('mass_matrix', request)
        n = len(response.name)
        if len(response.mass_matrix) != n * n:
            raise DynamicsError('service %s answered %d joints but %d mass-matrix entries'
                                % (self.service_name('mass_matrix'), n, len(response.mass_matrix)))
        matrix = np.array(response.mass_matrix, dtype=float).reshape(n, n)
        return MassMatrixResult(response.name, matrix, response.message)

    def inverse_dynamics_trajectory(self, positions, time_from_start=None, velocities=None, accelerations=None,
                                    joint_names=None, rigid_body_only=False):
        """Inverse dynamics at every point of a trajectory, as a TrajectoryResult.

        `positions` is a trajectory_msgs/JointTrajectory (sent as it is; the other arguments must
        then be None), or one row of positions per point, in the order of `joint_names` (None: the
        model's order, full rows). `time_from_start`: seconds (or rospy.Duration) per point; None:
        all 0, which only works when no differences are needed. `velocities`, `accelerations`:
        None (the node takes finite differences of the positions), or a row per point, where a
        row may be None (differences at that point)."""
        request = InverseDynamicsTrajectoryRequest()
        request.rigid_body_only = bool(rigid_body_only)
        if isinstance(positions, JointTrajectory):
            if any(x is not None for x in (time_from_start, velocities, accelerations, joint_names)):
                raise ValueError('a JointTrajectory carries its own times, velocities, accelerations and names')
            request.trajectory = positions
        else:
            rows = [[float(x) for x in np.asarray(row, dtype=float).ravel()] for row in positions]
            count = len(rows)

            def per_point(values, what):
                if values is None:
                    return [None] * count
                values = list(values)
                if len(values) != count:
                    raise ValueError('%s has %d entries but positions has %d points' % (what, len(values), count))
                return values

            times = per_point(time_from_start, 'time_from_start')
            vel = per_point(velocities, 'velocities')
            acc = per_point(accelerations, 'accelerations')
            request.trajectory.joint_names = list(joint_names or [])
            for k in range(count):
                point = JointTrajectoryPoint()
                point.positions = rows[k]
                if vel[k] is not None:
                    point.velocities = [float(x) for x in np.asarray(vel[k], dtype=float).ravel()]
                if acc[k] is not None:
                    point.accelerations = [float(x) for x in np.asarray(acc[k], dtype=float).ravel()]
                point.time_from_start = _duration(times[k] if times[k] is not None else 0.0)
                request.trajectory.points.append(point)
        return TrajectoryResult(self._call('inverse_dynamics_trajectory', request))

    # --- frames and payloads ----------------------------------------------------------------

    def transform_wrench(self, wrench, target_frame, position=None):
        """The same physical wrench expressed in `target_frame` about its origin, as a WrenchResult.
        `wrench`: as for external_wrenches (a WrenchStamped, WrenchResult, (frame, force[, torque]) or
        mapping). `position`: the configuration for robot frames (None: latest joint_states)."""
        request = TransformWrenchRequest()
        request.wrench = _to_wrench_stamped(wrench)
        request.target_frame = target_frame
        request.name, (request.position,) = _joint_arrays([('position', position, False)])
        response = self._call('transform_wrench', request)
        w = response.wrench
        return WrenchResult(w.header.frame_id, (w.wrench.force.x, w.wrench.force.y, w.wrench.force.z),
                            (w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z), w.header.stamp,
                            response.message)

    def set_contacts(self, contacts):
        """Replaces the node's contacts (~set_contacts) for every scene: [(frame, kind[, friction])
        or {frame, kind, friction}]; an empty list: none. Returns the node's message."""
        request = SetContactsRequest()
        request.frames, request.kinds, request.frictions = _contact_lists(contacts)
        return self._call('set_contacts', request).message

    def set_payload(self, frame, mass, center_of_mass=(0.0, 0.0, 0.0), inertia=None):
        """Attaches a rigid payload to `frame`: `mass` [kg], `center_of_mass` [m] in the frame,
        `inertia` [kg m^2] about the centre of mass in the frame's axes (3x3 symmetric, or
        (ixx, ixy, ixz, iyy, iyz, izz)). It replaces any payload on the frame; mass 0 removes it
        (as clear_payload). Returns the node's message."""
        request = SetPayloadRequest()
        request.frame = frame
        ixx, ixy, ixz, iyy, iyz, izz = (float(x) for x in _inertia_upper(np.zeros((3, 3)) if inertia is None else inertia))
        request.inertia = Inertia(m=float(mass), com=Point(*_vector3(center_of_mass, 'center_of_mass')),
                                  ixx=ixx, ixy=ixy, ixz=ixz, iyy=iyy, iyz=iyz, izz=izz)
        return self._call('set_payload', request).message

    def clear_payload(self, frame):
        """Removes the payload on `frame` (SetPayload with m = 0). Returns the node's message (which
        says so when there was none)."""
        request = SetPayloadRequest()
        request.frame = frame
        return self._call('set_payload', request).message

    # --- payload identification (doc/payload_identification.md) ------------------------------

    def excitation_trajectory(self, joints, duration, speed_scale=0.5, max_acceleration=0.0):
        """A rest-to-rest motion of `joints` over `duration` seconds that reveals a payload, within
        `speed_scale` of each joint's URDF velocity limit and position range and below
        `max_acceleration` (0: none), as an ExcitationResult (points every 10 ms)."""
        request = ExcitationTrajectoryRequest(joints=list(joints), duration=float(duration),
                                              speed_scale=float(speed_scale), max_acceleration=float(max_acceleration))
        return ExcitationResult(self._call('excitation_trajectory', request))

    def identify_payload(self, frame, samples=None, record_seconds=0.0, identify_friction=False, apply=False):
        """Identifies the payload on `frame` from `samples` (a trajectory_msgs/JointTrajectory whose
        points carry positions, velocities, optional accelerations and the measured `effort`), or from
        `record_seconds` of joint_states recorded by the node; with `apply` attaches it. Returns a
        PayloadResult."""
        request = IdentifyPayloadRequest(frame=frame, record_seconds=float(record_seconds),
                                         identify_friction=bool(identify_friction), apply=bool(apply))
        if samples is not None:
            request.samples = samples
        return PayloadResult(self._call('identify_payload', request))

    def reload(self):
        """Re-reads robot_description and ~gravity (std_srvs/Trigger). Returns the node's message."""
        return self._call('reload', TriggerRequest()).message
