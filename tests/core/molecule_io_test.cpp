// The molecule readers on the thermolysin ligands (SDF/MOL2/PDB), a pdb2pqr PQR file, a whole
// PDB structure, and a generated peptide that pins the protein lipophilicity table to RDKit's
// Wildman-Crippen typing; plus the errors bad input must raise.
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/pqr.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/protein_lipophilicity.hpp"
#include "test_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::io {
namespace {

namespace fs = std::filesystem;

// GACDEFGHIKLMNPQRSTVWYG at pH 7 (N-terminal NH3+, Asp/Glu/C-terminus COO-, Lys/Arg +),
// written by RDKit 2022.09 from SequenceToMol after setting those formal charges, embedded
// with ETKDGv3 (seed 42): heavy atoms only, in the same order in both blocks. RDKit's
// Crippen MolLogP of it is -16.7003.
constexpr const char* kPeptidePdb =
    R"(ATOM      1  N   GLY A   1       7.179   3.473  -5.160  1.00  0.00           N1+
ATOM      2  CA  GLY A   1       6.122   4.429  -5.466  1.00  0.00           C
ATOM      3  C   GLY A   1       4.810   3.747  -5.402  1.00  0.00           C
ATOM      4  O   GLY A   1       4.814   2.506  -5.096  1.00  0.00           O
ATOM      5  N   ALA A   2       3.569   4.381  -5.660  1.00  0.00           N
ATOM      6  CA  ALA A   2       2.362   3.557  -5.555  1.00  0.00           C
ATOM      7  C   ALA A   2       1.496   3.648  -6.752  1.00  0.00           C
ATOM      8  O   ALA A   2       1.774   4.510  -7.611  1.00  0.00           O
ATOM      9  CB  ALA A   2       1.549   4.260  -4.442  1.00  0.00           C
ATOM     10  N   CYS A   3       0.379   2.817  -6.974  1.00  0.00           N
ATOM     11  CA  CYS A   3      -0.507   2.861  -8.106  1.00  0.00           C
ATOM     12  C   CYS A   3      -1.889   2.511  -7.678  1.00  0.00           C
ATOM     13  O   CYS A   3      -2.055   2.114  -6.464  1.00  0.00           O
ATOM     14  CB  CYS A   3      -0.121   1.787  -9.122  1.00  0.00           C
ATOM     15  SG  CYS A   3      -0.214   0.141  -8.399  1.00  0.00           S
ATOM     16  N   ASP A   4      -3.018   2.594  -8.528  1.00  0.00           N
ATOM     17  CA  ASP A   4      -4.380   2.289  -8.153  1.00  0.00           C
ATOM     18  C   ASP A   4      -4.745   2.809  -6.849  1.00  0.00           C
ATOM     19  O   ASP A   4      -3.934   3.568  -6.231  1.00  0.00           O
ATOM     20  CB  ASP A   4      -4.699   0.871  -8.438  1.00  0.00           C
ATOM     21  CG  ASP A   4      -4.539   0.618  -9.909  1.00  0.00           C
ATOM     22  OD1 ASP A   4      -4.203   1.512 -10.717  1.00  0.00           O
ATOM     23  OD2 ASP A   4      -4.761  -0.644 -10.437  1.00  0.00           O1-
ATOM     24  N   GLU A   5      -5.965   2.564  -6.122  1.00  0.00           N
ATOM     25  CA  GLU A   5      -6.164   3.131  -4.820  1.00  0.00           C
ATOM     26  C   GLU A   5      -6.624   2.274  -3.761  1.00  0.00           C
ATOM     27  O   GLU A   5      -6.304   2.632  -2.566  1.00  0.00           O
ATOM     28  CB  GLU A   5      -6.951   4.419  -4.942  1.00  0.00           C
ATOM     29  CG  GLU A   5      -8.299   4.319  -5.522  1.00  0.00           C
ATOM     30  CD  GLU A   5      -8.278   3.821  -6.906  1.00  0.00           C
ATOM     31  OE1 GLU A   5      -9.089   2.894  -7.247  1.00  0.00           O
ATOM     32  OE2 GLU A   5      -7.381   4.375  -7.795  1.00  0.00           O1-
ATOM     33  N   PHE A   6      -7.394   1.066  -3.824  1.00  0.00           N
ATOM     34  CA  PHE A   6      -7.677   0.342  -2.637  1.00  0.00           C
ATOM     35  C   PHE A   6      -8.224  -1.018  -2.745  1.00  0.00           C
ATOM     36  O   PHE A   6      -9.159  -1.365  -3.483  1.00  0.00           O
ATOM     37  CB  PHE A   6      -8.734   1.125  -1.784  1.00  0.00           C
ATOM     38  CG  PHE A   6      -8.909   0.237  -0.583  1.00  0.00           C
ATOM     39  CD1 PHE A   6      -8.061   0.326   0.492  1.00  0.00           C
ATOM     40  CD2 PHE A   6      -9.931  -0.686  -0.526  1.00  0.00           C
ATOM     41  CE1 PHE A   6      -8.214  -0.470   1.600  1.00  0.00           C
ATOM     42  CE2 PHE A   6     -10.080  -1.486   0.592  1.00  0.00           C
ATOM     43  CZ  PHE A   6      -9.223  -1.394   1.678  1.00  0.00           C
ATOM     44  N   GLY A   7      -7.646  -2.067  -1.943  1.00  0.00           N
ATOM     45  CA  GLY A   7      -8.038  -3.426  -1.825  1.00  0.00           C
ATOM     46  C   GLY A   7      -6.879  -4.221  -1.264  1.00  0.00           C
ATOM     47  O   GLY A   7      -7.079  -5.352  -0.844  1.00  0.00           O
ATOM     48  N   HIS A   8      -5.592  -3.651  -1.259  1.00  0.00           N
ATOM     49  CA  HIS A   8      -4.367  -4.276  -0.777  1.00  0.00           C
ATOM     50  C   HIS A   8      -3.228  -3.382  -1.064  1.00  0.00           C
ATOM     51  O   HIS A   8      -2.029  -3.844  -0.919  1.00  0.00           O
ATOM     52  CB  HIS A   8      -4.194  -5.491  -1.750  1.00  0.00           C
ATOM     53  CG  HIS A   8      -3.015  -6.300  -1.478  1.00  0.00           C
ATOM     54  ND1 HIS A   8      -1.788  -6.189  -1.980  1.00  0.00           N
ATOM     55  CD2 HIS A   8      -2.960  -7.387  -0.613  1.00  0.00           C
ATOM     56  CE1 HIS A   8      -1.001  -7.141  -1.473  1.00  0.00           C
ATOM     57  NE2 HIS A   8      -1.723  -7.899  -0.613  1.00  0.00           N
ATOM     58  N   ILE A   9      -3.317  -2.048  -1.497  1.00  0.00           N
ATOM     59  CA  ILE A   9      -2.133  -1.210  -1.850  1.00  0.00           C
ATOM     60  C   ILE A   9      -1.904  -0.260  -0.782  1.00  0.00           C
ATOM     61  O   ILE A   9      -2.564  -0.404   0.320  1.00  0.00           O
ATOM     62  CB  ILE A   9      -2.337  -0.696  -3.232  1.00  0.00           C
ATOM     63  CG1 ILE A   9      -1.232   0.128  -3.806  1.00  0.00           C
ATOM     64  CG2 ILE A   9      -2.520  -1.927  -4.136  1.00  0.00           C
ATOM     65  CD1 ILE A   9      -2.734  -1.526  -5.570  1.00  0.00           C
ATOM     66  N   LYS A  10      -1.019   0.857  -0.755  1.00  0.00           N
ATOM     67  CA  LYS A  10      -0.851   1.712   0.378  1.00  0.00           C
ATOM     68  C   LYS A  10      -1.409   3.096   0.292  1.00  0.00           C
ATOM     69  O   LYS A  10      -1.486   3.683  -0.770  1.00  0.00           O
ATOM     70  CB  LYS A  10       0.692   1.900   0.438  1.00  0.00           C
ATOM     71  CG  LYS A  10       1.023   2.854   1.526  1.00  0.00           C
ATOM     72  CD  LYS A  10       2.543   3.042   1.564  1.00  0.00           C
ATOM     73  CE  LYS A  10       2.922   4.030   2.645  1.00  0.00           C
ATOM     74  NZ  LYS A  10       2.316   5.352   2.423  1.00  0.00           N1+
ATOM     75  N   LEU A  11      -1.856   3.724   1.518  1.00  0.00           N
ATOM     76  CA  LEU A  11      -2.358   5.037   1.629  1.00  0.00           C
ATOM     77  C   LEU A  11      -2.666   5.450   2.989  1.00  0.00           C
ATOM     78  O   LEU A  11      -2.867   6.696   3.245  1.00  0.00           O
ATOM     79  CB  LEU A  11      -3.492   5.320   0.655  1.00  0.00           C
ATOM     80  CG  LEU A  11      -4.712   4.519   0.771  1.00  0.00           C
ATOM     81  CD1 LEU A  11      -5.443   4.663   2.108  1.00  0.00           C
ATOM     82  CD2 LEU A  11      -4.550   3.037   0.440  1.00  0.00           C
ATOM     83  N   MET A  12      -2.791   4.605   4.137  1.00  0.00           N
ATOM     84  CA  MET A  12      -3.102   5.143   5.459  1.00  0.00           C
ATOM     85  C   MET A  12      -2.803   4.282   6.566  1.00  0.00           C
ATOM     86  O   MET A  12      -2.926   4.779   7.752  1.00  0.00           O
ATOM     87  CB  MET A  12      -4.624   5.443   5.403  1.00  0.00           C
ATOM     88  CG  MET A  12      -5.107   5.971   6.708  1.00  0.00           C
ATOM     89  SD  MET A  12      -4.282   7.478   7.242  1.00  0.00           S
ATOM     90  CE  MET A  12      -4.958   7.948   8.849  1.00  0.00           C
ATOM     91  N   ASN A  13      -2.388   2.945   6.495  1.00  0.00           N
ATOM     92  CA  ASN A  13      -2.134   2.193   7.728  1.00  0.00           C
ATOM     93  C   ASN A  13      -0.769   1.659   7.787  1.00  0.00           C
ATOM     94  O   ASN A  13      -0.552   0.578   7.174  1.00  0.00           O
ATOM     95  CB  ASN A  13      -3.131   1.004   7.770  1.00  0.00           C
ATOM     96  CG  ASN A  13      -4.520   1.492   7.757  1.00  0.00           C
ATOM     97  OD1 ASN A  13      -4.997   2.003   8.788  1.00  0.00           O
ATOM     98  ND2 ASN A  13      -5.367   1.407   6.608  1.00  0.00           N
ATOM     99  N   PRO A  14       0.282   2.274   8.470  1.00  0.00           N
ATOM    100  CA  PRO A  14       1.662   2.103   8.705  1.00  0.00           C
ATOM    101  C   PRO A  14       2.566   1.272   7.977  1.00  0.00           C
ATOM    102  O   PRO A  14       3.676   0.978   8.707  1.00  0.00           O
ATOM    103  CB  PRO A  14       1.641   1.878  10.229  1.00  0.00           C
ATOM    104  CG  PRO A  14       0.617   2.938  10.643  1.00  0.00           C
ATOM    105  CD  PRO A  14       0.021   3.485   9.332  1.00  0.00           C
ATOM    106  N   GLN A  15       2.635   0.692   6.745  1.00  0.00           N
ATOM    107  CA  GLN A  15       3.704  -0.138   6.161  1.00  0.00           C
ATOM    108  C   GLN A  15       4.366   0.658   5.147  1.00  0.00           C
ATOM    109  O   GLN A  15       3.773   1.810   4.928  1.00  0.00           O
ATOM    110  CB  GLN A  15       3.259  -1.508   5.953  1.00  0.00           C
ATOM    111  CG  GLN A  15       4.269  -2.419   5.331  1.00  0.00           C
ATOM    112  CD  GLN A  15       3.706  -3.808   5.315  1.00  0.00           C
ATOM    113  OE1 GLN A  15       2.508  -3.948   5.630  1.00  0.00           O
ATOM    114  NE2 GLN A  15       4.490  -4.908   4.960  1.00  0.00           N
ATOM    115  N   ARG A  16       5.523   0.413   4.367  1.00  0.00           N
ATOM    116  CA  ARG A  16       5.955   1.384   3.435  1.00  0.00           C
ATOM    117  C   ARG A  16       6.118   1.014   2.037  1.00  0.00           C
ATOM    118  O   ARG A  16       6.448   2.002   1.268  1.00  0.00           O
ATOM    119  CB  ARG A  16       7.274   2.074   3.838  1.00  0.00           C
ATOM    120  CG  ARG A  16       8.414   1.063   3.940  1.00  0.00           C
ATOM    121  CD  ARG A  16       9.651   1.876   4.332  1.00  0.00           C
ATOM    122  NE  ARG A  16       9.925   2.867   3.327  1.00  0.00           N
ATOM    123  CZ  ARG A  16      10.411   2.613   2.038  1.00  0.00           C
ATOM    124  NH1 ARG A  16      10.665   1.414   1.661  1.00  0.00           N1+
ATOM    125  NH2 ARG A  16      10.634   3.690   1.098  1.00  0.00           N
ATOM    126  N   SER A  17       5.984  -0.209   1.387  1.00  0.00           N
ATOM    127  CA  SER A  17       6.185  -0.366  -0.060  1.00  0.00           C
ATOM    128  C   SER A  17       5.024  -1.004  -0.661  1.00  0.00           C
ATOM    129  O   SER A  17       4.026  -1.255   0.074  1.00  0.00           O
ATOM    130  CB  SER A  17       7.496  -1.018  -0.399  1.00  0.00           C
ATOM    131  OG  SER A  17       7.668  -2.270   0.119  1.00  0.00           O
ATOM    132  N   THR A  18       4.859  -1.407  -2.028  1.00  0.00           N
ATOM    133  CA  THR A  18       3.636  -2.049  -2.459  1.00  0.00           C
ATOM    134  C   THR A  18       3.839  -3.424  -3.001  1.00  0.00           C
ATOM    135  O   THR A  18       4.954  -3.840  -3.332  1.00  0.00           O
ATOM    136  CB  THR A  18       3.120  -1.217  -3.623  1.00  0.00           C
ATOM    137  OG1 THR A  18       1.937  -1.747  -4.147  1.00  0.00           O
ATOM    138  CG2 THR A  18       4.137  -1.136  -4.760  1.00  0.00           C
ATOM    139  N   VAL A  19       2.707  -4.253  -3.121  1.00  0.00           N
ATOM    140  CA  VAL A  19       2.641  -5.592  -3.615  1.00  0.00           C
ATOM    141  C   VAL A  19       2.875  -6.637  -2.605  1.00  0.00           C
ATOM    142  O   VAL A  19       2.580  -7.842  -2.902  1.00  0.00           O
ATOM    143  CB  VAL A  19       3.459  -5.793  -4.878  1.00  0.00           C
ATOM    144  CG1 VAL A  19       3.325  -7.229  -5.340  1.00  0.00           C
ATOM    145  CG2 VAL A  19       2.745  -4.934  -5.943  1.00  0.00           C
ATOM    146  N   TRP A  20       3.404  -6.276  -1.368  1.00  0.00           N
ATOM    147  CA  TRP A  20       3.639  -7.187  -0.295  1.00  0.00           C
ATOM    148  C   TRP A  20       3.194  -6.497   0.989  1.00  0.00           C
ATOM    149  O   TRP A  20       3.669  -6.837   2.052  1.00  0.00           O
ATOM    150  CB  TRP A  20       5.027  -7.686  -0.111  1.00  0.00           C
ATOM    151  CG  TRP A  20       5.564  -8.436  -1.259  1.00  0.00           C
ATOM    152  CD1 TRP A  20       5.519  -9.802  -1.403  1.00  0.00           C
ATOM    153  CD2 TRP A  20       6.149  -7.924  -2.391  1.00  0.00           C
ATOM    154  NE1 TRP A  20       6.059 -10.108  -2.587  1.00  0.00           N
ATOM    155  CE2 TRP A  20       6.453  -8.980  -3.215  1.00  0.00           C
ATOM    156  CE3 TRP A  20       6.484  -6.659  -2.814  1.00  0.00           C
ATOM    157  CZ2 TRP A  20       7.075  -8.802  -4.457  1.00  0.00           C
ATOM    158  CZ3 TRP A  20       7.095  -6.468  -4.021  1.00  0.00           C
ATOM    159  CH2 TRP A  20       7.404  -7.535  -4.874  1.00  0.00           C
ATOM    160  N   TYR A  21       2.240  -5.470   0.890  1.00  0.00           N
ATOM    161  CA  TYR A  21       1.718  -4.620   1.925  1.00  0.00           C
ATOM    162  C   TYR A  21       0.694  -5.242   2.779  1.00  0.00           C
ATOM    163  O   TYR A  21       0.154  -4.509   3.663  1.00  0.00           O
ATOM    164  CB  TYR A  21       1.168  -3.401   1.266  1.00  0.00           C
ATOM    165  CG  TYR A  21       0.630  -2.328   2.095  1.00  0.00           C
ATOM    166  CD1 TYR A  21       1.532  -1.342   2.538  1.00  0.00           C
ATOM    167  CD2 TYR A  21      -0.690  -2.140   2.433  1.00  0.00           C
ATOM    168  CE1 TYR A  21       1.127  -0.258   3.260  1.00  0.00           C
ATOM    169  CE2 TYR A  21      -1.094  -1.031   3.170  1.00  0.00           C
ATOM    170  CZ  TYR A  21      -0.190  -0.077   3.588  1.00  0.00           C
ATOM    171  OH  TYR A  21      -0.629   1.014   4.309  1.00  0.00           O
ATOM    172  N   GLY A  22       0.300  -6.571   2.666  1.00  0.00           N
ATOM    173  CA  GLY A  22      -0.712  -7.066   3.581  1.00  0.00           C
ATOM    174  C   GLY A  22      -1.016  -8.481   3.357  1.00  0.00           C
ATOM    175  O   GLY A  22      -0.382  -9.115   2.447  1.00  0.00           O
ATOM    176  OXT GLY A  22      -1.983  -9.156   4.112  1.00  0.00           O1-
END
)";

constexpr const char* kPeptideSdf = R"(
     RDKit          3D

176181  0  0  0  0  0  0  0  0999 V2000
    7.1793    3.4728   -5.1599 N   0  0  0  0  0  4  0  0  0  0  0  0
    6.1216    4.4286   -5.4662 C   0  0  0  0  0  0  0  0  0  0  0  0
    4.8097    3.7474   -5.4024 C   0  0  0  0  0  0  0  0  0  0  0  0
    4.8143    2.5056   -5.0964 O   0  0  0  0  0  0  0  0  0  0  0  0
    3.5685    4.3812   -5.6598 N   0  0  0  0  0  0  0  0  0  0  0  0
    2.3621    3.5567   -5.5551 C   0  0  2  0  0  0  0  0  0  0  0  0
    1.4964    3.6481   -6.7520 C   0  0  0  0  0  0  0  0  0  0  0  0
    1.7741    4.5098   -7.6114 O   0  0  0  0  0  0  0  0  0  0  0  0
    1.5486    4.2605   -4.4423 C   0  0  0  0  0  0  0  0  0  0  0  0
    0.3790    2.8170   -6.9738 N   0  0  0  0  0  0  0  0  0  0  0  0
   -0.5067    2.8606   -8.1064 C   0  0  2  0  0  0  0  0  0  0  0  0
   -1.8893    2.5110   -7.6782 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.0550    2.1145   -6.4640 O   0  0  0  0  0  0  0  0  0  0  0  0
   -0.1209    1.7874   -9.1216 C   0  0  0  0  0  0  0  0  0  0  0  0
   -0.2142    0.1412   -8.3994 S   0  0  0  0  0  0  0  0  0  0  0  0
   -3.0175    2.5940   -8.5280 N   0  0  0  0  0  0  0  0  0  0  0  0
   -4.3804    2.2886   -8.1532 C   0  0  2  0  0  0  0  0  0  0  0  0
   -4.7450    2.8089   -6.8487 C   0  0  0  0  0  0  0  0  0  0  0  0
   -3.9345    3.5682   -6.2315 O   0  0  0  0  0  0  0  0  0  0  0  0
   -4.6994    0.8707   -8.4384 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.5386    0.6178   -9.9092 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.2032    1.5125  -10.7169 O   0  0  0  0  0  0  0  0  0  0  0  0
   -4.7614   -0.6442  -10.4372 O   0  0  0  0  0  1  0  0  0  0  0  0
   -5.9651    2.5643   -6.1222 N   0  0  0  0  0  0  0  0  0  0  0  0
   -6.1645    3.1307   -4.8201 C   0  0  2  0  0  0  0  0  0  0  0  0
   -6.6239    2.2745   -3.7612 C   0  0  0  0  0  0  0  0  0  0  0  0
   -6.3036    2.6322   -2.5657 O   0  0  0  0  0  0  0  0  0  0  0  0
   -6.9512    4.4193   -4.9421 C   0  0  0  0  0  0  0  0  0  0  0  0
   -8.2991    4.3186   -5.5218 C   0  0  0  0  0  0  0  0  0  0  0  0
   -8.2775    3.8214   -6.9057 C   0  0  0  0  0  0  0  0  0  0  0  0
   -9.0886    2.8942   -7.2468 O   0  0  0  0  0  0  0  0  0  0  0  0
   -7.3806    4.3753   -7.7947 O   0  0  0  0  0  1  0  0  0  0  0  0
   -7.3941    1.0657   -3.8238 N   0  0  0  0  0  0  0  0  0  0  0  0
   -7.6775    0.3417   -2.6371 C   0  0  2  0  0  0  0  0  0  0  0  0
   -8.2236   -1.0184   -2.7451 C   0  0  0  0  0  0  0  0  0  0  0  0
   -9.1591   -1.3654   -3.4835 O   0  0  0  0  0  0  0  0  0  0  0  0
   -8.7341    1.1254   -1.7839 C   0  0  0  0  0  0  0  0  0  0  0  0
   -8.9089    0.2367   -0.5834 C   0  0  0  0  0  0  0  0  0  0  0  0
   -8.0611    0.3265    0.4924 C   0  0  0  0  0  0  0  0  0  0  0  0
   -9.9310   -0.6862   -0.5263 C   0  0  0  0  0  0  0  0  0  0  0  0
   -8.2143   -0.4704    1.6004 C   0  0  0  0  0  0  0  0  0  0  0  0
  -10.0804   -1.4856    0.5920 C   0  0  0  0  0  0  0  0  0  0  0  0
   -9.2234   -1.3939    1.6780 C   0  0  0  0  0  0  0  0  0  0  0  0
   -7.6462   -2.0674   -1.9431 N   0  0  0  0  0  0  0  0  0  0  0  0
   -8.0384   -3.4259   -1.8250 C   0  0  0  0  0  0  0  0  0  0  0  0
   -6.8788   -4.2212   -1.2637 C   0  0  0  0  0  0  0  0  0  0  0  0
   -7.0792   -5.3517   -0.8438 O   0  0  0  0  0  0  0  0  0  0  0  0
   -5.5924   -3.6514   -1.2592 N   0  0  0  0  0  0  0  0  0  0  0  0
   -4.3673   -4.2759   -0.7775 C   0  0  2  0  0  0  0  0  0  0  0  0
   -3.2282   -3.3823   -1.0644 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.0295   -3.8439   -0.9186 O   0  0  0  0  0  0  0  0  0  0  0  0
   -4.1943   -5.4913   -1.7500 C   0  0  0  0  0  0  0  0  0  0  0  0
   -3.0152   -6.2999   -1.4777 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.7881   -6.1890   -1.9801 N   0  0  0  0  0  0  0  0  0  0  0  0
   -2.9603   -7.3869   -0.6127 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.0006   -7.1412   -1.4729 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.7231   -7.8994   -0.6132 N   0  0  0  0  0  0  0  0  0  0  0  0
   -3.3168   -2.0480   -1.4970 N   0  0  0  0  0  0  0  0  0  0  0  0
   -2.1333   -1.2101   -1.8500 C   0  0  2  0  0  0  0  0  0  0  0  0
   -1.9039   -0.2602   -0.7815 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.5643   -0.4043    0.3199 O   0  0  0  0  0  0  0  0  0  0  0  0
   -2.3370   -0.6962   -3.2318 C   0  0  1  0  0  0  0  0  0  0  0  0
   -1.2321    0.1281   -3.8065 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.5197   -1.9271   -4.1360 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.7342   -1.5258   -5.5703 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.0193    0.8570   -0.7547 N   0  0  0  0  0  0  0  0  0  0  0  0
   -0.8510    1.7122    0.3783 C   0  0  2  0  0  0  0  0  0  0  0  0
   -1.4087    3.0962    0.2915 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.4863    3.6828   -0.7700 O   0  0  0  0  0  0  0  0  0  0  0  0
    0.6921    1.9003    0.4381 C   0  0  0  0  0  0  0  0  0  0  0  0
    1.0230    2.8544    1.5258 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.5431    3.0420    1.5644 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.9217    4.0297    2.6451 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.3165    5.3519    2.4227 N   0  0  0  0  0  4  0  0  0  0  0  0
   -1.8558    3.7237    1.5178 N   0  0  0  0  0  0  0  0  0  0  0  0
   -2.3576    5.0367    1.6292 C   0  0  2  0  0  0  0  0  0  0  0  0
   -2.6656    5.4499    2.9886 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.8671    6.6959    3.2454 O   0  0  0  0  0  0  0  0  0  0  0  0
   -3.4916    5.3200    0.6550 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.7119    4.5187    0.7715 C   0  0  0  0  0  0  0  0  0  0  0  0
   -5.4426    4.6627    2.1076 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.5502    3.0365    0.4399 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.7912    4.6052    4.1373 N   0  0  0  0  0  0  0  0  0  0  0  0
   -3.1019    5.1429    5.4585 C   0  0  2  0  0  0  0  0  0  0  0  0
   -2.8028    4.2823    6.5662 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.9261    4.7792    7.7515 O   0  0  0  0  0  0  0  0  0  0  0  0
   -4.6243    5.4429    5.4030 C   0  0  0  0  0  0  0  0  0  0  0  0
   -5.1067    5.9711    6.7077 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.2816    7.4783    7.2422 S   0  0  0  0  0  0  0  0  0  0  0  0
   -4.9580    7.9477    8.8492 C   0  0  0  0  0  0  0  0  0  0  0  0
   -2.3877    2.9448    6.4946 N   0  0  0  0  0  0  0  0  0  0  0  0
   -2.1337    2.1926    7.7277 C   0  0  2  0  0  0  0  0  0  0  0  0
   -0.7685    1.6590    7.7872 C   0  0  0  0  0  0  0  0  0  0  0  0
   -0.5516    0.5779    7.1738 O   0  0  0  0  0  0  0  0  0  0  0  0
   -3.1313    1.0036    7.7700 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.5201    1.4919    7.7569 C   0  0  0  0  0  0  0  0  0  0  0  0
   -4.9966    2.0027    8.7875 O   0  0  0  0  0  0  0  0  0  0  0  0
   -5.3667    1.4072    6.6083 N   0  0  0  0  0  0  0  0  0  0  0  0
    0.2819    2.2742    8.4696 N   0  0  0  0  0  0  0  0  0  0  0  0
    1.6618    2.1028    8.7046 C   0  0  2  0  0  0  0  0  0  0  0  0
    2.5663    1.2715    7.9772 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.6757    0.9779    8.7068 O   0  0  0  0  0  0  0  0  0  0  0  0
    1.6414    1.8781   10.2288 C   0  0  0  0  0  0  0  0  0  0  0  0
    0.6166    2.9383   10.6426 C   0  0  0  0  0  0  0  0  0  0  0  0
    0.0215    3.4851    9.3317 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.6351    0.6918    6.7453 N   0  0  0  0  0  0  0  0  0  0  0  0
    3.7045   -0.1378    6.1611 C   0  0  2  0  0  0  0  0  0  0  0  0
    4.3657    0.6576    5.1473 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.7734    1.8100    4.9283 O   0  0  0  0  0  0  0  0  0  0  0  0
    3.2595   -1.5075    5.9528 C   0  0  0  0  0  0  0  0  0  0  0  0
    4.2690   -2.4186    5.3311 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.7059   -3.8082    5.3145 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.5077   -3.9480    5.6296 O   0  0  0  0  0  0  0  0  0  0  0  0
    4.4903   -4.9078    4.9602 N   0  0  0  0  0  0  0  0  0  0  0  0
    5.5229    0.4125    4.3667 N   0  0  0  0  0  0  0  0  0  0  0  0
    5.9547    1.3841    3.4347 C   0  0  2  0  0  0  0  0  0  0  0  0
    6.1176    1.0137    2.0375 C   0  0  0  0  0  0  0  0  0  0  0  0
    6.4476    2.0019    1.2679 O   0  0  0  0  0  0  0  0  0  0  0  0
    7.2739    2.0740    3.8384 C   0  0  0  0  0  0  0  0  0  0  0  0
    8.4136    1.0631    3.9400 C   0  0  0  0  0  0  0  0  0  0  0  0
    9.6506    1.8763    4.3317 C   0  0  0  0  0  0  0  0  0  0  0  0
    9.9246    2.8668    3.3268 N   0  0  0  0  0  0  0  0  0  0  0  0
   10.4110    2.6127    2.0384 C   0  0  0  0  0  0  0  0  0  0  0  0
   10.6654    1.4142    1.6609 N   0  0  0  0  0  4  0  0  0  0  0  0
   10.6342    3.6898    1.0982 N   0  0  0  0  0  0  0  0  0  0  0  0
    5.9837   -0.2086    1.3869 N   0  0  0  0  0  0  0  0  0  0  0  0
    6.1848   -0.3657   -0.0597 C   0  0  2  0  0  0  0  0  0  0  0  0
    5.0235   -1.0038   -0.6610 C   0  0  0  0  0  0  0  0  0  0  0  0
    4.0257   -1.2548    0.0736 O   0  0  0  0  0  0  0  0  0  0  0  0
    7.4964   -1.0177   -0.3993 C   0  0  0  0  0  0  0  0  0  0  0  0
    7.6681   -2.2697    0.1195 O   0  0  0  0  0  0  0  0  0  0  0  0
    4.8593   -1.4068   -2.0275 N   0  0  0  0  0  0  0  0  0  0  0  0
    3.6362   -2.0488   -2.4592 C   0  0  2  0  0  0  0  0  0  0  0  0
    3.8392   -3.4242   -3.0007 C   0  0  0  0  0  0  0  0  0  0  0  0
    4.9535   -3.8405   -3.3317 O   0  0  0  0  0  0  0  0  0  0  0  0
    3.1198   -1.2168   -3.6229 C   0  0  2  0  0  0  0  0  0  0  0  0
    1.9371   -1.7470   -4.1469 O   0  0  0  0  0  0  0  0  0  0  0  0
    4.1371   -1.1356   -4.7600 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.7071   -4.2529   -3.1207 N   0  0  0  0  0  0  0  0  0  0  0  0
    2.6408   -5.5920   -3.6153 C   0  0  2  0  0  0  0  0  0  0  0  0
    2.8752   -6.6371   -2.6054 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.5804   -7.8420   -2.9016 O   0  0  0  0  0  0  0  0  0  0  0  0
    3.4586   -5.7935   -4.8783 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.3255   -7.2285   -5.3396 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.7454   -4.9342   -5.9427 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.4041   -6.2764   -1.3684 N   0  0  0  0  0  0  0  0  0  0  0  0
    3.6394   -7.1871   -0.2946 C   0  0  2  0  0  0  0  0  0  0  0  0
    3.1938   -6.4972    0.9892 C   0  0  0  0  0  0  0  0  0  0  0  0
    3.6687   -6.8365    2.0518 O   0  0  0  0  0  0  0  0  0  0  0  0
    5.0268   -7.6862   -0.1109 C   0  0  0  0  0  0  0  0  0  0  0  0
    5.5645   -8.4363   -1.2590 C   0  0  0  0  0  0  0  0  0  0  0  0
    5.5186   -9.8024   -1.4025 C   0  0  0  0  0  0  0  0  0  0  0  0
    6.1489   -7.9245   -2.3913 C   0  0  0  0  0  0  0  0  0  0  0  0
    6.0590  -10.1082   -2.5875 N   0  0  0  0  0  0  0  0  0  0  0  0
    6.4528   -8.9797   -3.2145 C   0  0  0  0  0  0  0  0  0  0  0  0
    6.4839   -6.6594   -2.8142 C   0  0  0  0  0  0  0  0  0  0  0  0
    7.0749   -8.8025   -4.4571 C   0  0  0  0  0  0  0  0  0  0  0  0
    7.0948   -6.4677   -4.0212 C   0  0  0  0  0  0  0  0  0  0  0  0
    7.4039   -7.5346   -4.8742 C   0  0  0  0  0  0  0  0  0  0  0  0
    2.2403   -5.4703    0.8905 N   0  0  0  0  0  0  0  0  0  0  0  0
    1.7176   -4.6204    1.9250 C   0  0  2  0  0  0  0  0  0  0  0  0
    0.6937   -5.2415    2.7791 C   0  0  0  0  0  0  0  0  0  0  0  0
    0.1543   -4.5087    3.6631 O   0  0  0  0  0  0  0  0  0  0  0  0
    1.1682   -3.4014    1.2663 C   0  0  0  0  0  0  0  0  0  0  0  0
    0.6303   -2.3280    2.0950 C   0  0  0  0  0  0  0  0  0  0  0  0
    1.5320   -1.3422    2.5382 C   0  0  0  0  0  0  0  0  0  0  0  0
   -0.6899   -2.1399    2.4330 C   0  0  0  0  0  0  0  0  0  0  0  0
    1.1270   -0.2576    3.2597 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.0943   -1.0307    3.1698 C   0  0  0  0  0  0  0  0  0  0  0  0
   -0.1897   -0.0774    3.5881 C   0  0  0  0  0  0  0  0  0  0  0  0
   -0.6287    1.0141    4.3087 O   0  0  0  0  0  0  0  0  0  0  0  0
    0.3002   -6.5707    2.6661 N   0  0  0  0  0  0  0  0  0  0  0  0
   -0.7120   -7.0657    3.5807 C   0  0  0  0  0  0  0  0  0  0  0  0
   -1.0160   -8.4810    3.3569 C   0  0  0  0  0  0  0  0  0  0  0  0
   -0.3816   -9.1147    2.4471 O   0  0  0  0  0  0  0  0  0  0  0  0
   -1.9832   -9.1561    4.1120 O   0  0  0  0  0  1  0  0  0  0  0  0
  1  2  1  0
  2  3  1  0
  3  4  2  0
  5  6  1  0
  6  7  1  0
  7  8  2  0
  6  9  1  1
  3  5  1  0
 10 11  1  0
 11 12  1  0
 12 13  2  0
 11 14  1  6
 14 15  1  0
  7 10  1  0
 16 17  1  0
 17 18  1  0
 18 19  2  0
 17 20  1  1
 20 21  1  0
 21 22  2  0
 21 23  1  0
 12 16  1  0
 24 25  1  0
 25 26  1  0
 26 27  2  0
 25 28  1  6
 28 29  1  0
 29 30  1  0
 30 31  2  0
 30 32  1  0
 18 24  1  0
 33 34  1  0
 34 35  1  0
 35 36  2  0
 34 37  1  1
 37 38  1  0
 38 39  2  0
 39 41  1  0
 41 43  2  0
 43 42  1  0
 42 40  2  0
 40 38  1  0
 26 33  1  0
 44 45  1  0
 45 46  1  0
 46 47  2  0
 35 44  1  0
 48 49  1  0
 49 50  1  0
 50 51  2  0
 49 52  1  6
 52 53  1  0
 53 54  1  0
 54 56  2  0
 56 57  1  0
 57 55  1  0
 55 53  2  0
 46 48  1  0
 59 58  1  1
 59 60  1  0
 60 61  2  0
 59 62  1  0
 62 63  1  6
 62 64  1  0
 64 65  1  0
 50 58  1  0
 66 67  1  0
 67 68  1  0
 68 69  2  0
 67 70  1  6
 70 71  1  0
 71 72  1  0
 72 73  1  0
 73 74  1  0
 60 66  1  0
 75 76  1  0
 76 77  1  0
 77 78  2  0
 76 79  1  6
 79 80  1  0
 80 81  1  0
 80 82  1  0
 68 75  1  0
 83 84  1  0
 84 85  1  0
 85 86  2  0
 84 87  1  6
 87 88  1  0
 88 89  1  0
 89 90  1  0
 77 83  1  0
 91 92  1  0
 92 93  1  0
 93 94  2  0
 92 95  1  6
 95 96  1  0
 96 97  2  0
 96 98  1  0
 85 91  1  0
 99100  1  0
100101  1  6
101102  2  0
100103  1  0
103104  1  0
104105  1  0
105 99  1  0
 93 99  1  0
106107  1  0
107108  1  0
108109  2  0
107110  1  6
110111  1  0
111112  1  0
112113  2  0
112114  1  0
101106  1  0
115116  1  0
116117  1  0
117118  2  0
116119  1  1
119120  1  0
120121  1  0
121122  1  0
122123  1  0
123124  2  0
123125  1  0
108115  1  0
126127  1  0
127128  1  0
128129  2  0
127130  1  1
130131  1  0
117126  1  0
133132  1  6
133134  1  0
134135  2  0
133136  1  0
136137  1  0
136138  1  6
128132  1  0
140139  1  1
140141  1  0
141142  2  0
140143  1  0
143144  1  0
143145  1  0
134139  1  0
146147  1  0
147148  1  0
148149  2  0
147150  1  1
150151  1  0
151152  2  0
151153  1  0
152154  1  0
153155  2  0
153156  1  0
154155  1  0
155157  1  0
156158  2  0
157159  2  0
158159  1  0
141146  1  0
160161  1  0
161162  1  0
162163  2  0
161164  1  6
164165  1  0
165166  2  0
166168  1  0
168170  2  0
170169  1  0
169167  2  0
167165  1  0
170171  1  0
148160  1  0
172173  1  0
173174  1  0
174175  2  0
162172  1  0
174176  1  0
M  CHG  6   1   1  23  -1  32  -1  74   1 124   1 176  -1
M  END
$$$$
)";

// Alternate locations: SER 1 with CB and OG in A and B, residue 2 as ALA (A) or GLY (B)
// (microheterogeneity), and a sulfate present only as B.
constexpr const char* kAltlocPdb =
    R"(ATOM      1  N   SER A   1       0.000   0.000   0.000  1.00 10.00           N
ATOM      2  CA  SER A   1       1.458   0.000   0.000  1.00 10.00           C
ATOM      3  C   SER A   1       2.009   1.420   0.000  1.00 10.00           C
ATOM      4  O   SER A   1       1.251   2.390   0.000  1.00 10.00           O
ATOM      5  CB ASER A   1       1.988  -0.773  -1.199  0.60 10.00           C
ATOM      6  CB BSER A   1       1.988  -0.773   1.199  0.40 10.00           C
ATOM      7  OG ASER A   1       3.400  -0.800  -1.250  0.60 10.00           O
ATOM      8  OG BSER A   1       3.400  -0.800   1.250  0.40 10.00           O
ATOM      9  N  AALA A   2       3.332   1.547   0.000  0.50 10.00           N
ATOM     10  CA AALA A   2       3.956   2.862   0.000  0.50 10.00           C
ATOM     11  C  AALA A   2       5.470   2.732   0.000  0.50 10.00           C
ATOM     12  O  AALA A   2       6.020   1.631   0.000  0.50 10.00           O
ATOM     13  CB AALA A   2       3.500   3.650   1.220  0.50 10.00           C
ATOM     14  N  BGLY A   2       3.332   1.547   0.300  0.50 10.00           N
ATOM     15  CA BGLY A   2       3.956   2.862   0.300  0.50 10.00           C
ATOM     16  C  BGLY A   2       5.470   2.732   0.300  0.50 10.00           C
ATOM     17  O  BGLY A   2       6.020   1.631   0.300  0.50 10.00           O
HETATM   18  S  BSO4 A 101      12.000  12.000  12.000  0.30 10.00           S
HETATM   19  O1 BSO4 A 101      12.850  12.850  12.850  0.30 10.00           O
HETATM   20  O2 BSO4 A 101      11.150  11.150  12.850  0.30 10.00           O
HETATM   21  O3 BSO4 A 101      11.150  12.850  11.150  0.30 10.00           O
HETATM   22  O4 BSO4 A 101      12.850  11.150  11.150  0.30 10.00           O
END
)";

using test::TempDir;

MoleculeReadOptions ligand_options(const std::string& ligand) {
  MoleculeReadOptions options;
  options.ligand = ligand;
  return options;
}

MoleculeReadOptions charge_options(ChargeModel charges) {
  MoleculeReadOptions options;
  options.charges = charges;
  return options;
}

double total_charge(const Molecule& m) {
  return std::accumulate(m.atoms.begin(), m.atoms.end(), 0.0,
                         [](double s, const Atom& a) { return s + a.charge; });
}

double total_lipophilicity(const Molecule& m) {
  return std::accumulate(m.atoms.begin(), m.atoms.end(), 0.0,
                         [](double s, const Atom& a) { return s + a.lipophilicity; });
}

std::vector<const Atom*> heavy_atoms(const Molecule& m) {
  std::vector<const Atom*> heavy;
  for (const Atom& a : m.atoms) {
    if (a.element != "H") heavy.push_back(&a);
  }
  return heavy;
}

// ATOM/HETATM lines of a PDB/PQR text, optionally without water.
std::vector<std::string> atom_records(const fs::path& file, bool skip_water) {
  std::ifstream in(file);
  std::vector<std::string> records;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ATOM", 0) != 0 && line.rfind("HETATM", 0) != 0) continue;
    if (skip_water && line.size() > 20 && line.substr(17, 3) == "HOH") continue;
    records.push_back(line);
  }
  return records;
}

void expect_error_naming(const std::function<void()>& read, const std::string& name) {
  try {
    read();
    ADD_FAILURE() << "no exception for " << name;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(MoleculeIo, ExtensionsAreRecognisedCaseInsensitively) {
  for (const char* name : {"a.sdf", "a.MOL", "a.mol2", "a.PDB", "a.ent", "a.pqr"}) {
    EXPECT_TRUE(is_molecule_file(name)) << name;
  }
  for (const char* name : {"a.ply", "a.xyz", "a", "a.sdf.gz"}) {
    EXPECT_FALSE(is_molecule_file(name)) << name;
  }
}

TEST(MoleculeFormats, ExtensionsAndMessagesComeFromOneTable) {
  EXPECT_EQ(molecule_extensions(MoleculeUse::molecule),
            ".sdf .mol .mol2 .pdb .ent .cif .mmcif .cif.gz .pqr");
  EXPECT_EQ(molecule_extensions(MoleculeUse::records),
            ".sdf .mol .mol2 .pdb .ent .cif .mmcif .cif.gz .pqr .smi .dat .dat.gz");
  EXPECT_EQ(molecule_extensions(MoleculeUse::structure), ".pdb .ent .cif .mmcif .cif.gz");
  for (const MoleculeFormat& format : molecule_formats()) {
    const std::string name = "dir/X" + std::string(format.extension);
    SCOPED_TRACE(name);
    EXPECT_EQ(find_molecule_format(name), &format);
    EXPECT_FALSE(format.name.empty());
    EXPECT_TRUE(is_record_file(name));
    EXPECT_EQ(is_molecule_file(name), serves(format, MoleculeUse::molecule));
    EXPECT_EQ(is_structure_file(name), serves(format, MoleculeUse::structure));
    EXPECT_EQ(is_smiles_file(name), !serves(format, MoleculeUse::molecule));
  }
  // The longest ending is the format: a gzipped mmCIF file, not a .gz of nothing known.
  EXPECT_TRUE(is_mmcif_file("1abc.CIF.GZ"));
  EXPECT_EQ(find_molecule_format("list.dat.gz")->kind, MoleculeFileKind::table);
  EXPECT_EQ(find_molecule_format("x.gz"), nullptr);
  EXPECT_EQ(find_molecule_format("x.xyz"), nullptr);
  EXPECT_EQ(find_molecule_format(".sdf"), nullptr);  // a hidden file, not an extension
  // Messages list the table's extensions.
  try {
    read_molecule("x.xyz");
    ADD_FAILURE() << "x.xyz read";
  } catch (const FormatError& e) {
    EXPECT_NE(
        std::string(e.what()).find("(expected " + molecule_extensions(MoleculeUse::molecule) + ")"),
        std::string::npos)
        << e.what();
  }
}

TEST(MoleculeIo, ThermolysinLigandAgreesAcrossSdfMol2AndPdb) {
  SURFCOMP_SHARED_OR_SKIP(sdf_path, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  SURFCOMP_SHARED_OR_SKIP(mol2_path, "thermolysin/ligands-common-frame/1THL_ligand.mol2");
  SURFCOMP_SHARED_OR_SKIP(pdb_path, "thermolysin/ligands-common-frame/1THL_ligand.pdb");
  const Molecule sdf = read_molecule(sdf_path);
  const Molecule mol2 = read_molecule(mol2_path);
  const Molecule pdb = read_molecule(pdb_path, ligand_options("0DB"));

  // SDF and MOL2 list the 30 hydrogens; the PDB has the 35 heavy atoms only.
  ASSERT_EQ(sdf.atoms.size(), 65u);
  ASSERT_EQ(mol2.atoms.size(), 65u);
  ASSERT_EQ(pdb.atoms.size(), 35u);
  const auto sdf_heavy = heavy_atoms(sdf);
  const auto mol2_heavy = heavy_atoms(mol2);
  ASSERT_EQ(sdf_heavy.size(), 35u);
  ASSERT_EQ(mol2_heavy.size(), 35u);
  for (std::size_t i = 0; i < 35; ++i) {
    EXPECT_EQ(sdf_heavy[i]->element, pdb.atoms[i].element) << i;
    EXPECT_LT((sdf_heavy[i]->position - pdb.atoms[i].position).norm(), 1e-3) << i;
    EXPECT_LT((mol2_heavy[i]->position - pdb.atoms[i].position).norm(), 1e-3) << i;
  }
  EXPECT_EQ(pdb.atoms[0].name, "CA");
  EXPECT_EQ(pdb.atoms[0].residue_name, "0DB");
  EXPECT_DOUBLE_EQ(pdb.atoms[0].radius, 1.70);

  // Two carboxylates: SDF formal charge -2, reproduced by Gasteiger; MOL2 has GASTEIGER
  // charges in the file (sum -1.9999 as printed to 4 decimals).
  EXPECT_EQ(sdf.charge_source, ChargeSource::gasteiger);
  EXPECT_NEAR(total_charge(sdf), -2.0, 1e-9);
  EXPECT_EQ(mol2.charge_source, ChargeSource::file);
  EXPECT_NEAR(total_charge(mol2), -1.9999, 1e-9);
  EXPECT_NEAR(mol2.atoms[10].charge, -0.5495, 1e-12);  // O.co2, atom 11 in the file
  // PDB: no bond orders, proximity bonding gives a neutral single-bonded molecule.
  EXPECT_EQ(pdb.charge_source, ChargeSource::gasteiger);
  EXPECT_NEAR(total_charge(pdb), 0.0, 1e-9);

  // Wildman-Crippen: the sum over atoms is RDKit's MolLogP (1.8945 for this SDF, computed with
  // RDKit 2022.09 Crippen::calcClogP); the MOL2 is the same molecule after the pyrrole-N repair.
  EXPECT_TRUE(sdf.lipophilicity_assigned);
  EXPECT_NEAR(total_lipophilicity(sdf), 1.8945, 1e-9);
  EXPECT_NEAR(total_lipophilicity(mol2), 1.8945, 1e-9);
  EXPECT_TRUE(pdb.lipophilicity_assigned);
  EXPECT_GT(std::abs(total_lipophilicity(pdb)), 0.1);
  EXPECT_EQ(sdf.source, sdf_path.string());
  EXPECT_FALSE(sdf.title.empty());
}

TEST(MoleculeIo, LigandOnlyPdbWithoutSelectionIsTypedLikeTheSelection) {
  SURFCOMP_SHARED_OR_SKIP(pdb_path, "thermolysin/ligands-common-frame/1THL_ligand.pdb");
  const Molecule whole = read_molecule(pdb_path);
  const Molecule selected = read_molecule(pdb_path, ligand_options("0DB"));
  ASSERT_EQ(whole.atoms.size(), selected.atoms.size());
  for (std::size_t i = 0; i < whole.atoms.size(); ++i) {
    EXPECT_DOUBLE_EQ(whole.atoms[i].lipophilicity, selected.atoms[i].lipophilicity) << i;
  }
}

TEST(MoleculeIo, ChargeModelsOnTheSdfLigand) {
  SURFCOMP_SHARED_OR_SKIP(sdf_path, "thermolysin/ligands-common-frame/1THL_ligand.sdf");
  const Molecule gasteiger = read_molecule(sdf_path, charge_options(ChargeModel::gasteiger));
  const Molecule mmff = read_molecule(sdf_path, charge_options(ChargeModel::mmff));
  EXPECT_EQ(gasteiger.charge_source, ChargeSource::gasteiger);
  EXPECT_EQ(mmff.charge_source, ChargeSource::mmff);
  EXPECT_NEAR(total_charge(mmff), -2.0, 1e-6);
  // MMFF gives each carboxylate O -0.9 (bond-charge increments of O2CM).
  EXPECT_NEAR(mmff.atoms[10].charge, -0.9, 1e-6);
  double largest_difference = 0.0;
  for (std::size_t i = 0; i < mmff.atoms.size(); ++i) {
    largest_difference =
        std::max(largest_difference, std::abs(mmff.atoms[i].charge - gasteiger.atoms[i].charge));
  }
  EXPECT_GT(largest_difference, 0.1);
  MoleculeReadOptions no_lipophilicity;
  no_lipophilicity.assign_lipophilicity = false;
  const Molecule bare = read_molecule(sdf_path, no_lipophilicity);
  EXPECT_FALSE(bare.lipophilicity_assigned);
  EXPECT_EQ(total_lipophilicity(bare), 0.0);
}

TEST(MoleculeIo, Mol2WithoutChargesFallsBackToGasteiger) {
  SURFCOMP_FETCHED_OR_SKIP(path, "pdb2pqr-doc/LIG_1HPV.mol2");
  const Molecule m = read_molecule(path);
  EXPECT_EQ(m.charge_source, ChargeSource::gasteiger);
  ASSERT_EQ(m.atoms.size(), 70u);
  EXPECT_NEAR(total_charge(m), 0.0, 1e-9);
  double largest = 0.0;
  for (const Atom& a : m.atoms) largest = std::max(largest, std::abs(a.charge));
  EXPECT_GT(largest, 0.2);
  EXPECT_EQ(m.title, "LIM::478_200_pdb1hpv_1");
}

TEST(MoleculeIo, PqrChargesAndRadiiAreTakenAsGiven) {
  SURFCOMP_SHARED_OR_SKIP(path, "surfaces/lysozyme-msms/lys1_charges.pqr");
  const auto records = atom_records(path, false);
  const Molecule m = read_pqr(path);
  ASSERT_EQ(m.atoms.size(), records.size());
  ASSERT_EQ(m.atoms.size(), 1323u);
  EXPECT_EQ(m.charge_source, ChargeSource::file);
  double file_sum = 0.0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    std::istringstream fields(records[i]);
    std::vector<std::string> f;
    for (std::string s; fields >> s;) f.push_back(s);
    file_sum += std::stod(f[f.size() - 2]);
    EXPECT_DOUBLE_EQ(m.atoms[i].charge, std::stod(f[f.size() - 2])) << i;
    EXPECT_DOUBLE_EQ(m.atoms[i].radius, std::stod(f.back())) << i;
  }
  EXPECT_NEAR(total_charge(m), file_sum, 1e-9);
  EXPECT_NEAR(total_charge(m), 5.68, 1e-9);
  EXPECT_EQ(m.atoms[0].name, "N");
  EXPECT_EQ(m.atoms[0].residue_name, "LYS");
  EXPECT_EQ(m.atoms[1].element, "H");  // HT1
  // Whole protein: residue table, hydrogens 0, backbone N an amide NH.
  EXPECT_TRUE(m.lipophilicity_assigned);
  EXPECT_NEAR(m.atoms[0].lipophilicity, -0.7096 + 0.2142, 1e-12);
  EXPECT_EQ(m.atoms[1].lipophilicity, 0.0);
  // read_molecule dispatches .pqr to read_pqr; computed charge models are refused.
  EXPECT_EQ(read_molecule(path).atoms.size(), 1323u);
  EXPECT_THROW(read_molecule(path, charge_options(ChargeModel::gasteiger)), OptionError);
  EXPECT_THROW(read_pqr(path, charge_options(ChargeModel::mmff)), OptionError);
}

TEST(MoleculeIo, WholeThermolysinWithoutWaterAndItsInhibitor) {
  SURFCOMP_SHARED_OR_SKIP(path, "thermolysin/1THL.pdb");
  SURFCOMP_SHARED_OR_SKIP(original, "thermolysin/ligands-original/ligand1THL.pdb");
  const auto records = atom_records(path, true);
  const Molecule whole = read_molecule(path);
  ASSERT_EQ(whole.atoms.size(), records.size());
  EXPECT_EQ(whole.atoms.size(), 2472u);  // 2620 records minus 148 HOH
  for (const Atom& a : whole.atoms) EXPECT_NE(a.residue_name, "HOH");
  MoleculeReadOptions with_water;
  with_water.remove_water = false;
  const Molecule wet = read_molecule(path, with_water);
  EXPECT_EQ(wet.atoms.size(), 2620u);
  // Dropping the waters keeps the structure's title (RDKit's name from the HEADER), not the
  // file's stem.
  EXPECT_EQ(whole.title, wet.title);
  EXPECT_NE(whole.title, "1THL");
  EXPECT_FALSE(whole.title.empty());

  // The four Ca and the Zn have no Gasteiger parameters: ionic charges +2.
  int ions = 0;
  for (const Atom& a : whole.atoms) {
    if (a.element == "Ca" || a.element == "Zn") {
      ++ions;
      EXPECT_DOUBLE_EQ(a.charge, 2.0);
      EXPECT_EQ(a.lipophilicity, 0.0);
    }
  }
  EXPECT_EQ(ions, 5);
  // A protein from a PDB file gets residue charges (protein_charges.hpp), not Gasteiger.
  EXPECT_EQ(whole.charge_source, ChargeSource::residue_table);
  // The table gives the first residue's atoms their values (1THL starts with ILE 1).
  ASSERT_EQ(whole.atoms[0].residue_name, "ILE");
  EXPECT_NEAR(whole.atoms[1].lipophilicity, -0.2051 + 0.1230, 1e-12);  // CA
  // Residue 0DB is not a standard residue: 0 in the whole structure.
  for (const Atom& a : whole.atoms) {
    if (a.residue_name == "0DB") {
      EXPECT_EQ(a.lipophilicity, 0.0);
    }
  }

  const Molecule ligand = read_molecule(path, ligand_options("0DB"));
  const auto original_records = atom_records(original, false);
  ASSERT_EQ(original_records.size(), 35u);
  ASSERT_EQ(ligand.atoms.size(), original_records.size());
  EXPECT_EQ(heavy_atoms(ligand).size(), 35u);
  const Molecule original_ligand = read_molecule(original, ligand_options("0DB"));
  for (std::size_t i = 0; i < ligand.atoms.size(); ++i) {
    EXPECT_TRUE(ligand.atoms[i].hetero);
    EXPECT_LT((ligand.atoms[i].position - original_ligand.atoms[i].position).norm(), 1e-3);
    // Same residue, same proximity bonding: same Crippen increments.
    EXPECT_NEAR(ligand.atoms[i].lipophilicity, original_ligand.atoms[i].lipophilicity, 1e-12);
  }
}

TEST(MoleculeIo, PdbKeepsTheFirstAlternateLocationOfEveryAtom) {
  TempDir dir;
  const fs::path file = dir.write("altloc.pdb", kAltlocPdb);
  struct Expected {
    const char* residue;
    int number;
    const char* name;
    Eigen::Vector3d position;
  };
  const std::vector<Expected> expected = {
      {"SER", 1, "N", {0.000, 0.000, 0.000}},       {"SER", 1, "CA", {1.458, 0.000, 0.000}},
      {"SER", 1, "C", {2.009, 1.420, 0.000}},       {"SER", 1, "O", {1.251, 2.390, 0.000}},
      {"SER", 1, "CB", {1.988, -0.773, -1.199}},    {"SER", 1, "OG", {3.400, -0.800, -1.250}},
      {"ALA", 2, "N", {3.332, 1.547, 0.000}},       {"ALA", 2, "CA", {3.956, 2.862, 0.000}},
      {"ALA", 2, "C", {5.470, 2.732, 0.000}},       {"ALA", 2, "O", {6.020, 1.631, 0.000}},
      {"ALA", 2, "CB", {3.500, 3.650, 1.220}},      {"SO4", 101, "S", {12.000, 12.000, 12.000}},
      {"SO4", 101, "O1", {12.850, 12.850, 12.850}}, {"SO4", 101, "O2", {11.150, 11.150, 12.850}},
      {"SO4", 101, "O3", {11.150, 12.850, 11.150}}, {"SO4", 101, "O4", {12.850, 11.150, 11.150}}};
  const Molecule whole = read_molecule(file);
  ASSERT_EQ(whole.atoms.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const Atom& a = whole.atoms[i];
    EXPECT_EQ(a.residue_name, expected[i].residue) << i;
    EXPECT_EQ(a.residue_number, expected[i].number) << i;
    EXPECT_EQ(a.name, expected[i].name) << i;
    EXPECT_LT((a.position - expected[i].position).norm(), 1e-9) << i;
  }
  // The residue present only as B is a ligand like any other.
  const Molecule sulfate = read_molecule(file, ligand_options("SO4"));
  ASSERT_EQ(sulfate.atoms.size(), 5u);
  EXPECT_EQ(sulfate.atoms[0].element, "S");
  EXPECT_NEAR(total_charge(sulfate), 0.0, 1e-9);
}

TEST(MoleculeIo, KahramanSite1rdqAtpPresentOnlyAsAlternateLocationBIsRead) {
  SURFCOMP_SHARED_OR_SKIP(path, "kahraman-dev/pdb/1RDQ.pdb");
  // 2942 records, no water: 31 of ATP 600 E, all with alternate location B, and 41 atoms
  // elsewhere with both A and B.
  const auto records = atom_records(path, false);
  ASSERT_EQ(records.size(), 2942u);
  const Molecule whole = read_molecule(path);
  EXPECT_EQ(whole.atoms.size(), 2942u - 41u);
  const auto atp = std::count_if(whole.atoms.begin(), whole.atoms.end(), [](const Atom& a) {
    return a.residue_name == "ATP" && a.residue_number == 600 && a.chain == "E";
  });
  EXPECT_EQ(atp, 31);
}

TEST(ProteinLipophilicity, TableValuesAreUnitedWildmanCrippenAtoms) {
  // Types by hand, values from Wildman & Crippen 1999 Table 1.
  EXPECT_NEAR(*protein_atom_lipophilicity("ALA", "CB"), 0.1441 + 3 * 0.1230, 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity("LYS", "NZ"), -1.9500 + 3 * 0.2142, 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity("TYR", "OH"), -0.2893 - 0.2677, 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity("PRO", "N"), -0.3187, 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity(" asp", "OD1 "), 0.5 * (-0.1526 - 1.3260), 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity("CYX", "SG"), 0.6482, 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity("CYS", "SG"), 0.6482 - 0.2677, 1e-12);
  EXPECT_NEAR(*protein_atom_lipophilicity("GLY", "OXT"), -1.3260, 1e-12);
  EXPECT_EQ(*protein_atom_lipophilicity("HIS", "NE2"), *protein_atom_lipophilicity("HIE", "NE2"));
  EXPECT_NEAR(*protein_atom_lipophilicity("HID", "ND1") + *protein_atom_lipophilicity("HID", "NE2"),
              *protein_atom_lipophilicity("HIE", "ND1") + *protein_atom_lipophilicity("HIE", "NE2"),
              1e-12);
  EXPECT_EQ(*protein_atom_lipophilicity("LEU", "HD11"), 0.0);
  EXPECT_EQ(*protein_atom_lipophilicity("LYS", "1HZ"), 0.0);
  EXPECT_FALSE(protein_atom_lipophilicity("0DB", "CA").has_value());
  EXPECT_FALSE(protein_atom_lipophilicity("ALA", "CG").has_value());
}

TEST(ProteinLipophilicity, TableMatchesRdkitCrippenOnAPeptide) {
  TempDir dir;
  const Molecule table = read_molecule(dir.write("peptide.pdb", kPeptidePdb));
  const Molecule rdkit = read_molecule(dir.write("peptide.sdf", kPeptideSdf));
  ASSERT_EQ(table.atoms.size(), 176u);
  ASSERT_EQ(rdkit.atoms.size(), 176u);
  // RDKit's sum is its MolLogP; the table differs only at the N-terminus, typed as a backbone
  // amide NH (N2 + H3) where RDKit sees NH3+ (N10 + 3 H3): -0.4954 versus -1.3074.
  EXPECT_NEAR(total_lipophilicity(rdkit), -16.7003, 1e-9);
  EXPECT_NEAR(total_lipophilicity(table) - total_lipophilicity(rdkit), 0.8120, 1e-9);

  // Per atom: equal except the N-terminal N, the resonance pairs the table averages (their
  // sums agree) and Ile CG1/CG2, which RDKit's sequence template names the other way round.
  const std::set<std::pair<std::string, std::string>> averaged{
      {"ASP", "OD1"}, {"ASP", "OD2"}, {"GLU", "OE1"}, {"GLU", "OE2"},
      {"ARG", "NH1"}, {"ARG", "NH2"}, {"ILE", "CG1"}, {"ILE", "CG2"}};
  std::map<int, double> table_by_residue, rdkit_by_residue;
  int compared = 0;
  for (std::size_t i = 0; i < table.atoms.size(); ++i) {
    const Atom& a = table.atoms[i];
    EXPECT_LT((a.position - rdkit.atoms[i].position).norm(), 1e-3) << i;
    table_by_residue[a.residue_number] += a.lipophilicity;
    rdkit_by_residue[a.residue_number] += rdkit.atoms[i].lipophilicity;
    if (i == 0 || averaged.count({a.residue_name, a.name})) continue;
    EXPECT_NEAR(a.lipophilicity, rdkit.atoms[i].lipophilicity, 1e-9)
        << a.residue_name << a.residue_number << " " << a.name;
    ++compared;
  }
  EXPECT_EQ(compared, 176 - 1 - 8);
  for (const auto& [residue, sum] : table_by_residue) {
    if (residue == 1) continue;
    EXPECT_NEAR(sum, rdkit_by_residue[residue], 1e-9) << "residue " << residue;
  }
}

TEST(MoleculeIo, BadInputRaisesTheRightErrorNamingTheFile) {
  TempDir dir;
  const fs::path missing = dir.write("placeholder.txt", "").parent_path() / "missing.sdf";
  EXPECT_THROW(read_molecule(missing), FileError);
  expect_error_naming([&] { read_molecule(missing); }, "missing.sdf");
  EXPECT_THROW(read_molecule(dir.write("a.xyz", "1\n\nC 0 0 0\n")), FormatError);

  for (const char* name : {"empty.sdf", "empty.mol2", "empty.pdb", "empty.pqr"}) {
    const fs::path path = dir.write(name, "");
    EXPECT_THROW(read_molecule(path), InputError) << name;
    expect_error_naming([&] { read_molecule(path); }, name);
  }
  const std::string garbage = "this is not a molecule\n\x01\x02\xff garbage 1 2 3\n";
  for (const char* name : {"garbage.sdf", "garbage.mol2", "garbage.pdb", "garbage.pqr"}) {
    const fs::path path = dir.write(name, garbage);
    EXPECT_THROW(read_molecule(path), InputError) << name;
    expect_error_naming([&] { read_molecule(path); }, name);
  }
  const fs::path nan_pqr =
      dir.write("nan.pqr",
                "ATOM      1  N   LYS     1       3.294  10.164  10.266 -0.3200 1.5000\n"
                "ATOM      2  CA  LYS     1         nan   9.177  10.419  0.3300 2.0000\n");
  EXPECT_THROW(read_pqr(nan_pqr), InputError);
  expect_error_naming([&] { read_pqr(nan_pqr); }, "nan.pqr:2");
  const fs::path short_pqr =
      dir.write("short.pqr", "ATOM      1  N   LYS     1       3.294  10.164 -0.3200 1.5000\n");
  EXPECT_THROW(read_pqr(short_pqr), FormatError);
  // RDKit reads a repeated BOND section too, past the checks of the first: a second one naming
  // atom 0 crashed it (fuzz_mol2). One section of each kind per molecule.
  const fs::path repeated = dir.write("repeated.mol2",
                                      "@<TRIPOS>MOLECULE\nt\n 3 1\n\n@<TRIPOS>ATOM\n"
                                      "1 C1 0 0 0 C.3\n2 C2 1.5 0 0 C.3\n3 O3 2.2 1.1 0 O.3\n"
                                      "@<TRIPOS>BOND\n1 2 1 1\n@<TRIPOS>BOND\n1 1 0 1\n");
  EXPECT_THROW(read_molecule(repeated), FormatError);
  expect_error_naming([&] { read_molecule(repeated); }, "repeated.mol2:11");
  // RDKit takes a line whose first field is the name for a header, words after it too.
  const fs::path worded = dir.write("worded.mol2",
                                    "@<TRIPOS>MOLECULE\nt\n 3 1\n\n@<TRIPOS>ATOM\n"
                                    "1 C1 0 0 0 C.3\n2 C2 1.5 0 0 C.3\n3 O3 2.2 1.1 0 O.3\n"
                                    "@<TRIPOS>BOND\n1 2 1 1\n@<TRIPOS>BOND again\n1 1 0 1\n");
  expect_error_naming([&] { read_molecule(worded); }, "worded.mol2:11");

  SURFCOMP_SHARED_OR_SKIP(pdb, "thermolysin/1THL.pdb");
  try {
    read_molecule(pdb, ligand_options("XYZ"));
    FAIL() << "no exception for an absent ligand";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1THL.pdb"), std::string::npos) << what;
    EXPECT_NE(what.find("0DB"), std::string::npos) << what;
    EXPECT_NE(what.find("ZN"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace surfcomp::io
