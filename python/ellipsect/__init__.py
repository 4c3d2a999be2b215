"""Exact collision queries between ellipses (2D) and ellipsoids (3D).

Bindings of the C++ library ellipsect (docs/python.md). Scalar bodies (Ellipse,
Ellipsoid) and batches from numpy arrays (Ellipses, Ellipsoids) go to the same functions:
classify, overlap, first_contact, distance, signed_distance, closest_point (and, scalar
only, first_contact under rigid motion with body_at, perram_wertheim and
closest_approach), and in 2D
intersect_boundaries, overlap_area, iou and Niemitalo's tests. classify, overlap,
distance, signed_distance and first_contact also take a body and a HalfPlane (2D) or
HalfSpace (3D); classify, overlap and first_contact a Box2 / Box3, a Triangle2 / Triangle3 or a
TriangleMesh2 / TriangleMesh3 (the answer then names the triangle); collide_and_slide moves
a body through a list of half-spaces or a mesh. Among many bodies,
overlapping_pairs and earliest_contact (open space or a periodic box). Every number comes
from the library; batch answers equal the scalar ones bit for bit. Pictures: ellipsect.plot;
Dask: ellipsect.dask.
"""

from ._ellipsect import (  # noqa: F401
    BoundaryIntersection,
    Box2,
    Box3,
    BoundaryStatus,
    Circle,
    ClosestApproach2,
    ClosestApproach3,
    ClosestPoint2,
    ClosestPoint3,
    Contact2,
    Contact3,
    ContactArrays,
    ContactFunction,
    ContactFunctionStatus,
    ContactStatus,
    CrossingKind,
    Distance2,
    Distance3,
    DistanceArrays,
    DistanceStatus,
    Ellipse,
    Ellipses,
    Ellipsoid,
    Ellipsoids,
    HalfPlane,
    HalfSpace,
    InputError,
    MeshContact2,
    MeshContact3,
    MeshRelation,
    Options,
    OverlapArea,
    Pairs2,
    Pairs3,
    PolygonalOverlap,
    QuarticPoint,
    QuarticStatus,
    Relation,
    SegmentCircle,
    Side,
    Slide2,
    Slide3,
    SlideStatus,
    Triangle2,
    Triangle3,
    TriangleMesh2,
    TriangleMesh3,
    Verdict,
    body_at,
    circle_cover_overlap,
    classify,
    closest_approach,
    collide_and_slide,
    closest_point,
    closest_point_closed_form,
    closest_point_quartic,
    distance,
    earliest_contact,
    first_contact,
    intersect_boundaries,
    iou,
    niemitalo_error_bound,
    overlap,
    overlap_area,
    overlapping_pairs,
    pairs,
    perram_wertheim,
    polygonal_overlap,
    segment_circle,
    signed_distance,
    simd_target,
)

__version__ = "0.1.0"
