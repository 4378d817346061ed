//! Named indices of refraction, as in Mitsuba 3.
//!
//! [`IOR_TABLE`] is Mitsuba's `ior.h` (Hecht, *Optics*; 0–20 °C, ≈589 nm), looked up
//! case-insensitively by [`lookup_ior`]. [`CONDUCTOR_PRESETS`] are the complex IORs
//! η + i·k of every conductor `material` preset of Mitsuba 3 (66 names, `_palik` aliases
//! included) as its RGB variants use them: Mitsuba reduces its measured spectra (Palik/Luxpop
//! data) to linear sRGB and clamps negative components to 0. The values are Mitsuba 3.9.1's
//! own, read back from its `conductor` plugin by `scripts/conductor_presets.py`, so both
//! renderers use the same f32 numbers. Names are case-sensitive, as in Mitsuba.

use crate::Spectrum;

/// Mitsuba's named dielectric IORs (dimensionless).
pub const IOR_TABLE: &[(&str, f32)] = &[
    ("vacuum", 1.0),
    ("helium", 1.000036),
    ("hydrogen", 1.000132),
    ("air", 1.000277),
    ("carbon dioxide", 1.00045),
    ("water", 1.3330),
    ("acetone", 1.36),
    ("ethanol", 1.361),
    ("carbon tetrachloride", 1.461),
    ("glycerol", 1.4729),
    ("benzene", 1.501),
    ("silicone oil", 1.52045),
    ("bromine", 1.661),
    ("water ice", 1.31),
    ("fused quartz", 1.458),
    ("pyrex", 1.470),
    ("acrylic glass", 1.49),
    ("polypropylene", 1.49),
    ("bk7", 1.5046),
    ("sodium chloride", 1.544),
    ("amber", 1.55),
    ("pet", 1.5750),
    ("diamond", 2.419),
];

/// The IOR called `name` (case-insensitive); the error lists the valid names.
pub fn lookup_ior(name: &str) -> Result<f32, String> {
    let lower = name.to_lowercase();
    IOR_TABLE.iter().find(|(n, _)| *n == lower).map(|&(_, v)| v).ok_or_else(|| {
        let names: Vec<&str> = IOR_TABLE.iter().map(|(n, _)| *n).collect();
        format!("unknown IOR name \"{name}\"; valid choices are: {}", names.join(", "))
    })
}

/// A conductor preset: name, η (real part) and k (imaginary part) per RGB channel.
pub struct ConductorPreset {
    pub name: &'static str,
    pub eta: [f32; 3],
    pub k: [f32; 3],
}

/// Conductor `material` presets (RGB-variant values). `none` is Mitsuba's default: η = 0,
/// k = 1, a 100 % reflecting mirror.
pub const CONDUCTOR_PRESETS: &[ConductorPreset] = &[
    ConductorPreset { name: "none", eta: [0.0, 0.0, 0.0], k: [1.0, 1.0, 1.0] },
    ConductorPreset {
        name: "a-C",
        eta: [2.9440457820892334, 2.2271363735198975, 1.968161702156067],
        k: [0.8874648809432983, 0.7992985248565674, 0.8152899742126465],
    },
    ConductorPreset {
        name: "Ag",
        eta: [0.15527619421482086, 0.11672795563936234, 0.13838763535022736],
        k: [4.828354358673096, 3.122222423553467, 2.1469011306762695],
    },
    ConductorPreset {
        name: "Al",
        eta: [1.6575008630752563, 0.8804047107696533, 0.521244466304779],
        k: [9.223811149597168, 6.26950216293335, 4.8370041847229],
    },
    ConductorPreset {
        name: "AlAs",
        eta: [3.6052958965301514, 3.232937812805176, 2.2163186073303223],
        k: [0.0006794373039156199, 0.0, 0.007512709125876427],
    },
    ConductorPreset {
        name: "AlAs_palik",
        eta: [3.6052958965301514, 3.232937812805176, 2.2163186073303223],
        k: [0.0006794373039156199, 0.0, 0.007512709125876427],
    },
    ConductorPreset {
        name: "AlSb",
        eta: [0.0, 4.139374732971191, 4.669254302978516],
        k: [0.0, 0.09400907903909683, 1.300570011138916],
    },
    ConductorPreset {
        name: "AlSb_palik",
        eta: [0.0, 4.139374732971191, 4.669254302978516],
        k: [0.0, 0.09400907903909683, 1.300570011138916],
    },
    ConductorPreset {
        name: "Au",
        eta: [0.14303597807884216, 0.3753070831298828, 1.4420453310012817],
        k: [3.982996940612793, 2.38555645942688, 1.6033592224121094],
    },
    ConductorPreset {
        name: "Be",
        eta: [4.185012340545654, 3.1850292682647705, 2.7840611934661865],
        k: [3.835465908050537, 3.010122299194336, 2.8689939975738525],
    },
    ConductorPreset {
        name: "Be_palik",
        eta: [4.185012340545654, 3.1850292682647705, 2.7840611934661865],
        k: [3.835465908050537, 3.010122299194336, 2.8689939975738525],
    },
    ConductorPreset {
        name: "Cr",
        eta: [4.3696675300598145, 2.9165053367614746, 1.6549046039581299],
        k: [5.206546783447266, 4.231306076049805, 3.7546987533569336],
    },
    ConductorPreset {
        name: "CsI",
        eta: [2.144899606704712, 1.7023189067840576, 1.6624271869659424],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "CsI_palik",
        eta: [2.144899606704712, 1.7023189067840576, 1.6624271869659424],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "Cu",
        eta: [0.2010054737329483, 0.9237495064735413, 1.1022154092788696],
        k: [3.913262128829956, 2.453045129776001, 2.14208984375],
    },
    ConductorPreset {
        name: "Cu_palik",
        eta: [0.2132285088300705, 0.919715404510498, 1.1024107933044434],
        k: [3.9218733310699463, 2.457331657409668, 2.1365840435028076],
    },
    ConductorPreset {
        name: "Cu2O",
        eta: [3.5517725944519043, 2.9498696327209473, 2.751875400543213],
        k: [0.11420702189207077, 0.19389685988426208, 0.6061338782310486],
    },
    ConductorPreset {
        name: "Cu2O_palik",
        eta: [3.5517725944519043, 2.9498696327209473, 2.751875400543213],
        k: [0.11420702189207077, 0.19389685988426208, 0.6061338782310486],
    },
    ConductorPreset {
        name: "CuO",
        eta: [3.2475409507751465, 2.447805166244507, 2.210219621658325],
        k: [0.5210895538330078, 0.5700307488441467, 0.7221789360046387],
    },
    ConductorPreset {
        name: "CuO_palik",
        eta: [3.2475409507751465, 2.447805166244507, 2.210219621658325],
        k: [0.5210895538330078, 0.5700307488441467, 0.7221789360046387],
    },
    ConductorPreset {
        name: "d-C",
        eta: [2.7087197303771973, 2.3188257217407227, 2.2288975715637207],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "d-C_palik",
        eta: [2.7087197303771973, 2.3188257217407227, 2.2288975715637207],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "Hg",
        eta: [2.3989386558532715, 1.4400279521942139, 0.9095703959465027],
        k: [6.327587127685547, 4.371924877166748, 3.4217636585235596],
    },
    ConductorPreset {
        name: "Hg_palik",
        eta: [2.3989386558532715, 1.4400279521942139, 0.9095703959465027],
        k: [6.327587127685547, 4.371924877166748, 3.4217636585235596],
    },
    ConductorPreset {
        name: "HgTe",
        eta: [4.7790398597717285, 3.231196165084839, 2.6599011421203613],
        k: [1.6316126585006714, 1.5808104276657104, 1.7292873859405518],
    },
    ConductorPreset {
        name: "HgTe_palik",
        eta: [4.7790398597717285, 3.231196165084839, 2.6599011421203613],
        k: [1.6316126585006714, 1.5808104276657104, 1.7292873859405518],
    },
    ConductorPreset {
        name: "Ir",
        eta: [3.0862998962402344, 2.08219051361084, 1.6179145574569702],
        k: [5.592153072357178, 4.0670881271362305, 3.2673120498657227],
    },
    ConductorPreset {
        name: "Ir_palik",
        eta: [3.0862998962402344, 2.08219051361084, 1.6179145574569702],
        k: [5.592153072357178, 4.0670881271362305, 3.2673120498657227],
    },
    ConductorPreset {
        name: "K",
        eta: [0.06404318660497665, 0.046409767121076584, 0.038184914737939835],
        k: [2.1041996479034424, 1.3489400148391724, 0.9131258726119995],
    },
    ConductorPreset {
        name: "K_palik",
        eta: [0.06404318660497665, 0.046409767121076584, 0.038184914737939835],
        k: [2.1041996479034424, 1.3489400148391724, 0.9131258726119995],
    },
    ConductorPreset {
        name: "Li",
        eta: [0.2657909393310547, 0.19561831653118134, 0.22094862163066864],
        k: [3.5401549339294434, 2.3111233711242676, 1.668607234954834],
    },
    ConductorPreset {
        name: "Li_palik",
        eta: [0.2657909393310547, 0.19561831653118134, 0.22094862163066864],
        k: [3.5401549339294434, 2.3111233711242676, 1.668607234954834],
    },
    ConductorPreset {
        name: "MgO",
        eta: [2.0895838737487793, 1.6507234573364258, 1.5948790311813354],
        k: [4.332695226899608e-12, 0.0, 2.4986457347608848e-11],
    },
    ConductorPreset {
        name: "MgO_palik",
        eta: [2.0895838737487793, 1.6507234573364258, 1.5948790311813354],
        k: [4.332695226899608e-12, 0.0, 2.4986457347608848e-11],
    },
    ConductorPreset {
        name: "Mo",
        eta: [4.483973979949951, 3.5251307487487793, 2.776310443878174],
        k: [4.1114373207092285, 3.4208269119262695, 3.1506073474884033],
    },
    ConductorPreset {
        name: "Mo_palik",
        eta: [4.483973979949951, 3.5251307487487793, 2.776310443878174],
        k: [4.1114373207092285, 3.4208269119262695, 3.1506073474884033],
    },
    ConductorPreset {
        name: "Na_palik",
        eta: [0.06026935577392578, 0.056140948086977005, 0.061988431960344315],
        k: [3.1792733669281006, 2.11249041557312, 1.5790411233901978],
    },
    ConductorPreset {
        name: "Nb",
        eta: [3.420073986053467, 2.790093183517456, 2.395629405975342],
        k: [3.441394567489624, 2.737666130065918, 2.5797457695007324],
    },
    ConductorPreset {
        name: "Nb_palik",
        eta: [3.420073986053467, 2.790093183517456, 2.395629405975342],
        k: [3.441394567489624, 2.737666130065918, 2.5797457695007324],
    },
    ConductorPreset {
        name: "Ni_palik",
        eta: [2.367304563522339, 1.6633731126785278, 1.4670780897140503],
        k: [4.498811721801758, 3.0501530170440674, 2.3454391956329346],
    },
    ConductorPreset {
        name: "Rh",
        eta: [2.5857934951782227, 1.8602163791656494, 1.5542633533477783],
        k: [6.782260417938232, 4.702987194061279, 3.9760730266571045],
    },
    ConductorPreset {
        name: "Rh_palik",
        eta: [2.5857934951782227, 1.8602163791656494, 1.5542633533477783],
        k: [6.782260417938232, 4.702987194061279, 3.9760730266571045],
    },
    ConductorPreset {
        name: "Se",
        eta: [4.058311462402344, 2.842935085296631, 2.8208534717559814],
        k: [0.75404953956604, 0.6384435296058655, 0.5218075513839722],
    },
    ConductorPreset {
        name: "Se_palik",
        eta: [4.058311462402344, 2.842935085296631, 2.8208534717559814],
        k: [0.75404953956604, 0.6384435296058655, 0.5218075513839722],
    },
    ConductorPreset {
        name: "SiC",
        eta: [3.1723415851593018, 2.5259716510772705, 2.479370594024658],
        k: [7.537663577750209e-07, 0.0, 1.0192530680797063e-05],
    },
    ConductorPreset {
        name: "SiC_palik",
        eta: [3.1723415851593018, 2.5259716510772705, 2.479370594024658],
        k: [7.537663577750209e-07, 0.0, 1.0192530680797063e-05],
    },
    ConductorPreset {
        name: "SnTe",
        eta: [4.52424955368042, 1.9816449880599976, 1.2815912961959839],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "SnTe_palik",
        eta: [4.52424955368042, 1.9816449880599976, 1.2815912961959839],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "Ta",
        eta: [2.062721014022827, 2.3929388523101807, 2.6279287338256836],
        k: [2.4083597660064697, 1.7414864301681519, 1.9470278024673462],
    },
    ConductorPreset {
        name: "Ta_palik",
        eta: [2.062721014022827, 2.3929388523101807, 2.6279287338256836],
        k: [2.4083597660064697, 1.7414864301681519, 1.9470278024673462],
    },
    ConductorPreset {
        name: "Te",
        eta: [7.390233516693115, 4.482104778289795, 2.637105941772461],
        k: [3.2560222148895264, 3.5270588397979736, 3.2920541763305664],
    },
    ConductorPreset {
        name: "Te_palik",
        eta: [7.390233516693115, 4.482104778289795, 2.637105941772461],
        k: [3.2560222148895264, 3.5270588397979736, 3.2920541763305664],
    },
    ConductorPreset {
        name: "ThF4",
        eta: [1.8307136297225952, 1.4422285556793213, 1.3876476287841797],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "ThF4_palik",
        eta: [1.8307136297225952, 1.4422285556793213, 1.3876476287841797],
        k: [0.0, 0.0, 0.0],
    },
    ConductorPreset {
        name: "TiC",
        eta: [3.700528383255005, 2.8374221324920654, 2.582287073135376],
        k: [3.2656350135803223, 2.3515892028808594, 2.17279052734375],
    },
    ConductorPreset {
        name: "TiC_palik",
        eta: [3.700528383255005, 2.8374221324920654, 2.582287073135376],
        k: [3.2656350135803223, 2.3515892028808594, 2.17279052734375],
    },
    ConductorPreset {
        name: "TiN",
        eta: [1.6484496593475342, 1.1505160331726074, 1.3798234462738037],
        k: [3.368328094482422, 1.943498134613037, 1.1020677089691162],
    },
    ConductorPreset {
        name: "TiN_palik",
        eta: [1.6484496593475342, 1.1505160331726074, 1.3798234462738037],
        k: [3.368328094482422, 1.943498134613037, 1.1020677089691162],
    },
    ConductorPreset {
        name: "TiO2",
        eta: [3.4566099643707275, 2.8017358779907227, 2.905174970626831],
        k: [0.00010526483674766496, 0.0, 0.0006528865196742117],
    },
    ConductorPreset {
        name: "TiO2_palik",
        eta: [3.4566099643707275, 2.8017358779907227, 2.905174970626831],
        k: [0.00010526483674766496, 0.0, 0.0006528865196742117],
    },
    ConductorPreset {
        name: "VC",
        eta: [3.6575660705566406, 2.7527360916137695, 2.5326719284057617],
        k: [3.068300724029541, 2.1986873149871826, 1.9631927013397217],
    },
    ConductorPreset {
        name: "VC_palik",
        eta: [3.6575660705566406, 2.7527360916137695, 2.5326719284057617],
        k: [3.068300724029541, 2.1986873149871826, 1.9631927013397217],
    },
    ConductorPreset {
        name: "V_palik",
        eta: [4.277582168579102, 3.512948751449585, 2.7610714435577393],
        k: [3.4913008213043213, 2.8894548416137695, 3.1115219593048096],
    },
    ConductorPreset {
        name: "VN",
        eta: [2.8656022548675537, 2.1191890239715576, 1.9400911331176758],
        k: [3.0322425365448, 2.0561156272888184, 1.6163063049316406],
    },
    ConductorPreset {
        name: "VN_palik",
        eta: [2.8656022548675537, 2.1191890239715576, 1.9400911331176758],
        k: [3.0322425365448, 2.0561156272888184, 1.6163063049316406],
    },
    ConductorPreset {
        name: "W",
        eta: [4.370816707611084, 3.300246477127075, 2.9984073638916016],
        k: [3.500640630722046, 2.6048738956451416, 2.27323317527771],
    },
];

/// (η, k) of the conductor preset `name` (case-sensitive, like Mitsuba's file names).
pub fn conductor_preset(name: &str) -> Result<(Spectrum, Spectrum), String> {
    CONDUCTOR_PRESETS
        .iter()
        .find(|p| p.name == name)
        .map(|p| (Spectrum::from(p.eta), Spectrum::from(p.k)))
        .ok_or_else(|| {
            let names: Vec<&str> = CONDUCTOR_PRESETS.iter().map(|p| p.name).collect();
            format!(
                "unknown conductor material \"{name}\"; supported presets are: {}",
                names.join(", ")
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookups() {
        assert_eq!(lookup_ior("bk7").unwrap(), 1.5046);
        assert_eq!(lookup_ior("Air").unwrap(), 1.000277);
        assert_eq!(lookup_ior("water ice").unwrap(), 1.31);
        let e = lookup_ior("glass").unwrap_err();
        assert!(e.contains("bk7") && e.contains("diamond"), "{e}");
        let (eta, k) = conductor_preset("none").unwrap();
        assert_eq!((eta, k), (Spectrum::ZERO, Spectrum::ONE));
        // Mitsuba 3.9.1's values for gold (its `conductor` plugin, scalar_rgb), to the last bit
        let (eta, k) = conductor_preset("Au").unwrap();
        assert_eq!(eta, Spectrum::new(0.14303597807884216, 0.3753070831298828, 1.4420453310012817));
        assert_eq!(k, Spectrum::new(3.982996940612793, 2.38555645942688, 1.6033592224121094));
        // the presets Mitsuba's documentation scenes use, and names differing only by case
        assert!(conductor_preset("a-C").is_ok() && conductor_preset("Cu_palik").is_ok());
        assert!(conductor_preset("au").is_err());
        assert_eq!(CONDUCTOR_PRESETS.len(), 66);
        let e = conductor_preset("Unobtainium").unwrap_err();
        assert!(e.contains("Cu") && e.contains("none"), "{e}");
    }
}
