// ellipsect: exact collision queries between ellipses and ellipsoids: the core library
// (target ellipsect::ellipsect). The modules built on it are outside this header, each with
// its own header and target: <ellipsect/packing.hpp>, ellipsect::packing (modules/packing).
#pragma once

#include <ellipsect/batch.hpp>
#include <ellipsect/box.hpp>
#include <ellipsect/capsule.hpp>
#include <ellipsect/broad_phase.hpp>
#include <ellipsect/classify.hpp>
#include <ellipsect/contact.hpp>
#include <ellipsect/contact_function.hpp>
#include <ellipsect/distance.hpp>
#include <ellipsect/geometry.hpp>
#include <ellipsect/gpu.hpp>
#include <ellipsect/gradient.hpp>
#include <ellipsect/half_space.hpp>
#include <ellipsect/margin.hpp>
#include <ellipsect/slide.hpp>
#include <ellipsect/intersect2.hpp>
#include <ellipsect/mesh.hpp>
#include <ellipsect/obstacles.hpp>
#include <ellipsect/options.hpp>
#include <ellipsect/parallel.hpp>
#include <ellipsect/point.hpp>
#include <ellipsect/polygonal2.hpp>
#include <ellipsect/quartic2.hpp>
#include <ellipsect/shapes.hpp>
#include <ellipsect/triangle.hpp>
#include <ellipsect/version.hpp>
