#include "fluid/vdb_export.h"

#ifdef MFX_HAVE_OPENVDB
#include <openvdb/openvdb.h>
#endif

#include <algorithm>
#include <cmath>

namespace mfx::fluid {

#ifdef MFX_HAVE_OPENVDB

bool vdbAvailable() {
    return true;
}

Status writeVdb(const std::string& path, const VdbFrame& frame) {
    if (frame.state == nullptr) return Error{path + ": no fields to write"};
    const FieldState& s = *frame.state;
    const GridShape& g = s.grid;
    if (frame.storedCells && !frame.storedCells->empty() &&
        frame.storedCells->size() != g.cellCount())
        return Error{path + ": the stored cells' flags do not match the grid"};
    openvdb::initialize();

    // Index space -> world: scale by h, move voxel 0's centre to the first cell's centre, then
    // (z up) turn y-up axes into z-up ones.
    const double h = double(g.cellSize);
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.preScale(openvdb::math::Vec3d(h));
    const glm::dvec3 first = glm::dvec3(frame.origin) + 0.5 * h;
    m.postTranslate(openvdb::math::Vec3d(first.x, first.y, first.z));
    if (frame.up == VdbUp::Z) {
        // (x, y, z) -> (x, -z, y): a rotation of +90 degrees about x.
        openvdb::math::Mat4d turn = openvdb::math::Mat4d::identity();
        turn.setRow(1, openvdb::math::Vec4d(0, 0, 1, 0));
        turn.setRow(2, openvdb::math::Vec4d(0, -1, 0, 0));
        m = m * turn; // OpenVDB maps row vectors: v' = v * m
    }
    const openvdb::math::Transform::Ptr transform =
        openvdb::math::Transform::createLinearTransform(m);

    openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(0.0f);
    openvdb::Vec3fGrid::Ptr colour = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    openvdb::Vec3fGrid::Ptr velocity = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.0f));
    auto densityAccess = density->getAccessor();
    auto colourAccess = colour->getAccessor();
    auto velocityAccess = velocity->getAccessor();
    const std::vector<float>* faces[3] = {&s.velocityX, &s.velocityY, &s.velocityZ};
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i) {
                const size_t cell = g.index(i, j, k);
                if (frame.storedCells && !frame.storedCells->empty() && !(*frame.storedCells)[cell])
                    continue;
                const openvdb::Coord at{int(i), int(j), int(k)};
                const float* p = &s.pigment[4 * cell];
                if (!(p[3] > 0.0f && std::isfinite(p[3]))) continue; // no smoke here
                densityAccess.setValue(at, p[3]);
                const float a = std::max(p[3], 1e-4f);
                colourAccess.setValue(at, openvdb::Vec3f(std::max(p[0] / a, 0.0f),
                                                         std::max(p[1] / a, 0.0f),
                                                         std::max(p[2] / a, 0.0f)));
                openvdb::Vec3f u;
                for (int c = 0; c < 3; ++c) {
                    const glm::uvec3 n = faceExtent(g, c);
                    glm::uvec3 hi(i, j, k);
                    hi[c] += 1;
                    u[c] = 0.5f * ((*faces[c])[i + n.x * (j + size_t(n.y) * k)] +
                                   (*faces[c])[hi.x + n.x * (hi.y + size_t(n.y) * hi.z)]);
                }
                if (frame.up == VdbUp::Z) u = openvdb::Vec3f(u[0], -u[2], u[1]);
                velocityAccess.setValue(at, u);
            }
    density->setName("density");
    density->setGridClass(openvdb::GRID_FOG_VOLUME);
    openvdb::FloatGrid::Ptr solid;
    if (frame.solidCells && frame.solidCells->size() == g.cellCount()) {
        solid = openvdb::FloatGrid::create(0.0f);
        auto solidAccess = solid->getAccessor();
        for (uint32_t k = 0; k < g.cellsZ; ++k)
            for (uint32_t j = 0; j < g.cellsY; ++j)
                for (uint32_t i = 0; i < g.cellsX; ++i)
                    if ((*frame.solidCells)[g.index(i, j, k)])
                        solidAccess.setValue(openvdb::Coord{int(i), int(j), int(k)}, 1.0f);
        solid->setName("solid");
        solid->setGridClass(openvdb::GRID_FOG_VOLUME);
    }
    colour->setName("colour");
    velocity->setName("velocity");
    velocity->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
    openvdb::GridPtrVec grids;
    for (openvdb::GridBase::Ptr grid :
         {openvdb::GridBase::Ptr(density), openvdb::GridBase::Ptr(colour),
          openvdb::GridBase::Ptr(velocity)}) {
        grid->setTransform(transform->copy());
        grid->setSaveFloatAsHalf(false);
        grids.push_back(grid);
    }
    if (solid) {
        solid->setTransform(transform->copy());
        solid->setSaveFloatAsHalf(false);
        grids.push_back(solid);
    }
    try {
        openvdb::io::File file(path);
        openvdb::MetaMap meta;
        meta.insertMeta("creator", openvdb::StringMetadata("motionfx"));
        file.write(grids, meta);
        file.close();
    } catch (const std::exception& e) {
        return Error{path + ": cannot write the OpenVDB file (" + e.what() + ")"};
    }
    return Ok{};
}

#else

bool vdbAvailable() {
    return false;
}

Status writeVdb(const std::string& path, const VdbFrame&) {
    return Error{path + ": this build has no OpenVDB (Debian: libopenvdb-dev and "
                        "libboost-iostreams-dev; ./build.sh deps installs them)"};
}

#endif

} // namespace mfx::fluid
