// meshctl --size-grid with rasters (GDAL): a GeoTIFF written here becomes a grid term with its
// rows flipped to y-up and origin and spacing from the pixel centres of its geotransform; the
// flags override them; rotated rasters, no-data pixels and a missing geotransform are refused,
// naming the flag and the file.
#include "client/size_grid.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/common/error.h"
#include "tests/client/gis_test_files.h"

namespace meshd::cli {
namespace {

// A float32 GeoTIFF of `rows` (top row first, as in the file); `gt` the geotransform, if any.
void write_tif(const std::string& path, const std::vector<std::vector<float>>& rows,
               std::optional<std::array<double, 6>> gt, std::optional<double> no_data = {}) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(driver, nullptr);
  const int width = static_cast<int>(rows[0].size()), height = static_cast<int>(rows.size());
  GDALDatasetUniquePtr data(driver->Create(path.c_str(), width, height, 1, GDT_Float32, nullptr));
  ASSERT_TRUE(data);
  if (gt) {
    ASSERT_EQ(data->SetGeoTransform(gt->data()), CE_None);
  }
  GDALRasterBand* band = data->GetRasterBand(1);
  if (no_data) band->SetNoDataValue(*no_data);
  for (int r = 0; r < height; ++r) {
    std::vector<float> row = rows[r];
    ASSERT_EQ(band->RasterIO(GF_Write, 0, r, width, 1, row.data(), width, 1, GDT_Float32, 0, 0),
              CE_None);
  }
}

// File row r, column i holds 10 r + i + 1: row 0 is the top (north) row.
std::vector<std::vector<float>> numbered(int width, int height) {
  std::vector<std::vector<float>> rows(height, std::vector<float>(width));
  for (int r = 0; r < height; ++r)
    for (int i = 0; i < width; ++i) rows[r][i] = static_cast<float>(10 * r + i + 1);
  return rows;
}

void expect_refused(const SizeGridOptions& o, const std::vector<std::string>& parts) {
  try {
    read_size_grid(o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "--size-grid");
    for (const auto& part : parts)
      EXPECT_NE(e.detail().find(part), std::string::npos) << e.detail() << "\nlacks: " << part;
  }
}

TEST(SizeGridRaster, NorthUpGeoTiffBecomesAGridWithRowsUpwards) {
  const testing::TempDir dir;
  SizeGridOptions o;
  o.path = dir.path("sizes.tif");
  // 4 columns, 3 rows of 10 x 20 pixels; the top-left corner at (100, 500).
  write_tif(o.path, numbered(4, 3), std::array<double, 6>{100, 10, 0, 500, 0, -20});
  const v1::GridSize g = read_size_grid(o);
  EXPECT_EQ(g.nx(), 4u);
  EXPECT_EQ(g.ny(), 3u);
  EXPECT_DOUBLE_EQ(g.origin().x(), 105);  // the bottom-left pixel's centre
  EXPECT_DOUBLE_EQ(g.origin().y(), 450);
  EXPECT_DOUBLE_EQ(g.spacing().x(), 10);
  EXPECT_DOUBLE_EQ(g.spacing().y(), 20);
  ASSERT_EQ(g.values_size(), 12);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(g.values(j * 4 + i), 10 * (2 - j) + i + 1) << "sample " << i << ", " << j;

  // The flags replace the geotransform's origin and spacing.
  o.origin = Vec2{0, 0};
  o.spacing = Vec2{1, 2};
  const v1::GridSize moved = read_size_grid(o);
  EXPECT_DOUBLE_EQ(moved.origin().y(), 0);
  EXPECT_DOUBLE_EQ(moved.spacing().y(), 2);
  EXPECT_EQ(moved.values(0), 21);
}

TEST(SizeGridRaster, RefusesRotationNoDataAndAMissingGeotransform) {
  const testing::TempDir dir;
  SizeGridOptions rotated;
  rotated.path = dir.path("rotated.tif");
  write_tif(rotated.path, numbered(3, 3), std::array<double, 6>{0, 10, 2, 0, 0, -10});
  expect_refused(rotated, {"rotated.tif", "rotated or sheared", "north-up"});

  SizeGridOptions gap;
  gap.path = dir.path("gap.tif");
  auto rows = numbered(3, 2);
  rows[0][1] = -9999;
  write_tif(gap.path, rows, std::array<double, 6>{0, 1, 0, 2, 0, -1}, -9999.0);
  expect_refused(gap, {"gap.tif", "column 1, row 0 (from the top) has no data"});

  SizeGridOptions bare;
  bare.path = dir.path("bare.tif");
  write_tif(bare.path, numbered(3, 2), std::nullopt);
  expect_refused(bare, {"bare.tif", "no geotransform", "--size-grid-origin"});
  bare.origin = Vec2{0, 0};
  bare.spacing = Vec2{1, 1};
  EXPECT_EQ(read_size_grid(bare).values(0), 11);  // the bottom row first

  SizeGridOptions negative;
  negative.path = dir.path("negative.tif");
  rows = numbered(3, 2);
  rows[1][2] = -1;
  write_tif(negative.path, rows, std::array<double, 6>{0, 1, 0, 2, 0, -1});
  expect_refused(negative, {"negative.tif", "[0, 2]", "must be finite and > 0"});

  SizeGridOptions missing;
  missing.path = dir.path("missing.tif");
  expect_refused(missing, {"missing.tif", "no such file"});
}

}  // namespace
}  // namespace meshd::cli
