//! The Butcher tableaux of the explicit Runge–Kutta methods (RK4, Butcher's order 6, Cooper and Verner's order 8,
//! the Dormand–Prince pairs of orders 5(4) and 8(5,3)) and their continuous extensions, checked against the order
//! conditions.

/// The weights of the classic fourth-order stages (RK4 and the RKMK4 methods).
pub(super) const RK4_WEIGHTS: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];

/// An explicit Runge–Kutta tableau with `S` stages: `a` strictly lower triangular, weights `b`, nodes `c`.
pub(super) struct Tableau<const S: usize> {
    pub(super) a: [[f64; S]; S],
    pub(super) b: [f64; S],
    pub(super) c: [f64; S],
    /// The order of the method, which sets where `dexp⁻¹` may be truncated.
    pub(super) order: u32,
}

/// The classic fourth-order tableau (for [`JointMethod::Rkmk4`]; the body methods write its stages out).
pub(super) const RK4: Tableau<4> = Tableau {
    a: [
        [0.0; 4],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: RK4_WEIGHTS,
    c: [0.0, 0.5, 0.5, 1.0],
    order: 4,
};

/// Butcher's 7-stage method of order 6 (J. C. Butcher, "On Runge–Kutta processes of high order", J. Austral.
/// Math. Soc. 4, 1964; the tableau as printed in his "Numerical Methods for Ordinary Differential Equations").
/// `integrate::tests::butcher_6_satisfies_the_order_conditions` checks all 37 order conditions up to order 6.
pub(super) const BUTCHER_6: Tableau<7> = Tableau {
    a: [
        [0.0; 7],
        [1.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0 / 12.0, 1.0 / 3.0, -1.0 / 12.0, 0.0, 0.0, 0.0, 0.0],
        [-1.0 / 16.0, 9.0 / 8.0, -3.0 / 16.0, -3.0 / 8.0, 0.0, 0.0, 0.0],
        [0.0, 9.0 / 8.0, -3.0 / 8.0, -3.0 / 4.0, 1.0 / 2.0, 0.0, 0.0],
        [
            9.0 / 44.0,
            -9.0 / 11.0,
            63.0 / 44.0,
            18.0 / 11.0,
            0.0,
            -16.0 / 11.0,
            0.0,
        ],
    ],
    b: [
        11.0 / 120.0,
        0.0,
        27.0 / 40.0,
        27.0 / 40.0,
        -4.0 / 15.0,
        -4.0 / 15.0,
        11.0 / 120.0,
    ],
    c: [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0, 1.0 / 2.0, 1.0 / 2.0, 1.0],
    order: 6,
};

/// √21, to the last bit of an f64 (`const` arithmetic has no square root): 4.582575694955840006588047193728…
pub(super) const SQRT_21: f64 = 4.582_575_694_955_84;

/// Cooper and Verner's 11-stage method of order 8 (G. J. Cooper and J. H. Verner, "Some explicit Runge–Kutta
/// methods of high order", SIAM J. Numer. Anal. 9(3), 1972), whose nodes are those of the Lobatto quadrature
/// of order 8 (½ and ½ ± √21/14). `integrate::tests::cooper_verner_8_satisfies_the_order_conditions` checks all
/// 200 order conditions up to order 8.
pub(super) const COOPER_VERNER_8: Tableau<11> = {
    const R: f64 = SQRT_21;
    const HIGH: f64 = (7.0 + R) / 14.0;
    const LOW: f64 = (7.0 - R) / 14.0;
    Tableau {
        a: [
            row(&[]),
            row(&[0.5]),
            row(&[0.25, 0.25]),
            row(&[1.0 / 7.0, (-7.0 - 3.0 * R) / 98.0, (21.0 + 5.0 * R) / 49.0]),
            row(&[(11.0 + R) / 84.0, 0.0, (18.0 + 4.0 * R) / 63.0, (21.0 - R) / 252.0]),
            row(&[
                (5.0 + R) / 48.0,
                0.0,
                (9.0 + R) / 36.0,
                (-231.0 + 14.0 * R) / 360.0,
                (63.0 - 7.0 * R) / 80.0,
            ]),
            row(&[
                (10.0 - R) / 42.0,
                0.0,
                (-432.0 + 92.0 * R) / 315.0,
                (633.0 - 145.0 * R) / 90.0,
                (-504.0 + 115.0 * R) / 70.0,
                (63.0 - 13.0 * R) / 35.0,
            ]),
            row(&[
                1.0 / 14.0,
                0.0,
                0.0,
                0.0,
                (14.0 - 3.0 * R) / 126.0,
                (13.0 - 3.0 * R) / 63.0,
                1.0 / 9.0,
            ]),
            row(&[
                1.0 / 32.0,
                0.0,
                0.0,
                0.0,
                (91.0 - 21.0 * R) / 576.0,
                11.0 / 72.0,
                (-385.0 - 75.0 * R) / 1152.0,
                (63.0 + 13.0 * R) / 128.0,
            ]),
            row(&[
                1.0 / 14.0,
                0.0,
                0.0,
                0.0,
                1.0 / 9.0,
                (-733.0 - 147.0 * R) / 2205.0,
                (515.0 + 111.0 * R) / 504.0,
                (-51.0 - 11.0 * R) / 56.0,
                (132.0 + 28.0 * R) / 245.0,
            ]),
            row(&[
                0.0,
                0.0,
                0.0,
                0.0,
                (-42.0 + 7.0 * R) / 18.0,
                (-18.0 + 28.0 * R) / 45.0,
                (-273.0 - 53.0 * R) / 72.0,
                (301.0 + 53.0 * R) / 72.0,
                (28.0 - 28.0 * R) / 45.0,
                (49.0 - 7.0 * R) / 18.0,
            ]),
        ],
        b: [
            1.0 / 20.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            49.0 / 180.0,
            16.0 / 45.0,
            49.0 / 180.0,
            1.0 / 20.0,
        ],
        c: [0.0, 0.5, 0.5, HIGH, HIGH, 0.5, LOW, LOW, 0.5, HIGH, 1.0],
        order: 8,
    }
};

/// Dormand and Prince's 7-stage pair (J. R. Dormand and P. J. Prince, J. Comp. Appl. Math. 6(1), 1980): the weights
/// of the 5th-order solution, which is kept, equal the last row (the last stage is the next step's first in the
/// classical method; here the step's end is projected or turned afterwards, so it is evaluated anew).
/// `integrate::tests::dormand_prince_5_satisfies_the_order_conditions` checks the 17 conditions up to order 5, the
/// embedded solution's 8 up to order 4, and the continuous extension's 8 at several points of the step.
pub(super) const DORMAND_PRINCE_5: Tableau<7> = Tableau {
    a: [
        row(&[]),
        row(&[1.0 / 5.0]),
        row(&[3.0 / 40.0, 9.0 / 40.0]),
        row(&[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0]),
        row(&[19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0]),
        row(&[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ]),
        row(&DORMAND_PRINCE_5_WEIGHTS),
    ],
    b: row(&DORMAND_PRINCE_5_WEIGHTS),
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    order: 5,
};

/// The weights of Dormand and Prince's 5th-order solution (stages 1–6; the 7th weighs 0).
pub(super) const DORMAND_PRINCE_5_WEIGHTS: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];

/// `b − b̂`: the 5th-order weights minus those of the embedded 4th-order solution (5179/57600, 0, 7571/16695,
/// 393/640, −92097/339200, 187/2100, 1/40).
pub(super) const DORMAND_PRINCE_5_ERROR: [f64; 7] = [
    35.0 / 384.0 - 5179.0 / 57600.0,
    0.0,
    500.0 / 1113.0 - 7571.0 / 16695.0,
    125.0 / 192.0 - 393.0 / 640.0,
    -2187.0 / 6784.0 + 92097.0 / 339200.0,
    11.0 / 84.0 - 187.0 / 2100.0,
    -1.0 / 40.0,
];

/// The continuous extension of order 4 (Shampine, "Some practical Runge–Kutta formulas", Math. Comp. 46, 1986; as
/// tabulated in Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6): the weight of stage i at the fraction θ of the
/// step is `Σₖ P[i][k] θ^(k+1)`, which equals the 5th-order weight at θ = 1.
pub(super) const DORMAND_PRINCE_5_DENSE: [[f64; 4]; 7] = [
    [
        1.0,
        -8048581381.0 / 2820520608.0,
        8663915743.0 / 2820520608.0,
        -12715105075.0 / 11282082432.0,
    ],
    [0.0; 4],
    [
        0.0,
        131558114200.0 / 32700410799.0,
        -68118460800.0 / 10900136933.0,
        87487479700.0 / 32700410799.0,
    ],
    [
        0.0,
        -1754552775.0 / 470086768.0,
        14199869525.0 / 1410260304.0,
        -10690763975.0 / 1880347072.0,
    ],
    [
        0.0,
        127303824393.0 / 49829197408.0,
        -318862633887.0 / 49829197408.0,
        701980252875.0 / 199316789632.0,
    ],
    [
        0.0,
        -282668133.0 / 205662961.0,
        2019193451.0 / 616988883.0,
        -1453857185.0 / 822651844.0,
    ],
    [
        0.0,
        40617522.0 / 29380423.0,
        -110615467.0 / 29380423.0,
        69997945.0 / 29380423.0,
    ],
];

/// The dense-output weights of [`DORMAND_PRINCE_5_DENSE`] at the fraction `theta` of the step.
pub(super) fn dormand_prince_5_dense_weights(theta: f64) -> [f64; 7] {
    DORMAND_PRINCE_5_DENSE.map(|p| theta * (p[0] + theta * (p[1] + theta * (p[2] + theta * p[3]))))
}

/// Dormand and Prince's 12-stage method of order 8 with embedded solutions of orders 5 and 3 (P. J. Prince and
/// J. R. Dormand, "High order embedded Runge–Kutta formulae", J. Comp. Appl. Math. 7(1), 1981; the coefficients as
/// published with Hairer's DOP853, in Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.10, to 30 digits).
/// `integrate::tests::dop853_satisfies_the_order_conditions` checks the 200 conditions up to order 8, the embedded
/// solutions' up to orders 5 and 3, and the continuous extension's up to order 7 at several points of the step.
#[allow(clippy::excessive_precision)] // the coefficients as published; each rounds to the nearest f64
pub(super) const DOP853: Tableau<12> = Tableau {
    a: [
        row(&[]),
        row(&[5.26001519587677318785587544488e-2]),
        row(&[1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2]),
        row(&[
            2.95875854768068491816892993775e-2,
            0.0,
            8.87627564304205475450678981324e-2,
        ]),
        row(&[
            2.41365134159266685502369798665e-1,
            0.0,
            -8.84549479328286085344864962717e-1,
            9.24834003261792003115737966543e-1,
        ]),
        row(&[
            3.7037037037037037037037037037e-2,
            0.0,
            0.0,
            1.70828608729473871279604482173e-1,
            1.25467687566822425016691814123e-1,
        ]),
        row(&[
            3.7109375e-2,
            0.0,
            0.0,
            1.70252211019544039314978060272e-1,
            6.02165389804559606850219397283e-2,
            -1.7578125e-2,
        ]),
        row(&[
            3.70920001185047927108779319836e-2,
            0.0,
            0.0,
            1.70383925712239993810214054705e-1,
            1.07262030446373284651809199168e-1,
            -1.53194377486244017527936158236e-2,
            8.27378916381402288758473766002e-3,
        ]),
        row(&[
            6.24110958716075717114429577812e-1,
            0.0,
            0.0,
            -3.36089262944694129406857109825,
            -8.68219346841726006818189891453e-1,
            2.75920996994467083049415600797e1,
            2.01540675504778934086186788979e1,
            -4.34898841810699588477366255144e1,
        ]),
        row(&[
            4.77662536438264365890433908527e-1,
            0.0,
            0.0,
            -2.48811461997166764192642586468,
            -5.90290826836842996371446475743e-1,
            2.12300514481811942347288949897e1,
            1.52792336328824235832596922938e1,
            -3.32882109689848629194453265587e1,
            -2.03312017085086261358222928593e-2,
        ]),
        row(&[
            -9.3714243008598732571704021658e-1,
            0.0,
            0.0,
            5.18637242884406370830023853209,
            1.09143734899672957818500254654,
            -8.14978701074692612513997267357,
            -1.85200656599969598641566180701e1,
            2.27394870993505042818970056734e1,
            2.49360555267965238987089396762,
            -3.0467644718982195003823669022,
        ]),
        row(&[
            2.27331014751653820792359768449,
            0.0,
            0.0,
            -1.05344954667372501984066689879e1,
            -2.00087205822486249909675718444,
            -1.79589318631187989172765950534e1,
            2.79488845294199600508499808837e1,
            -2.85899827713502369474065508674,
            -8.87285693353062954433549289258,
            1.23605671757943030647266201528e1,
            6.43392746015763530355970484046e-1,
        ]),
    ],
    b: DOP853_WEIGHTS,
    c: [
        0.0,
        0.526001519587677318785587544488e-1,
        0.789002279381515978178381316732e-1,
        0.118350341907227396726757197510,
        0.281649658092772603273242802490,
        1.0 / 3.0,
        0.25,
        4.0 / 13.0,
        127.0 / 195.0,
        0.6,
        6.0 / 7.0,
        1.0,
    ],
    order: 8,
};

/// The weights of DOP853's 8th-order solution.
#[allow(clippy::excessive_precision)]
pub(super) const DOP853_WEIGHTS: [f64; 12] = [
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
];

/// `b − b̂₅`: the 8th-order weights minus those of the embedded 5th-order solution.
#[allow(clippy::excessive_precision)]
pub(super) const DOP853_ERROR_5: [f64; 12] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];

/// `b − b̂₃`: the 8th-order weights minus those of the embedded 3rd-order solution, whose only weights are on
/// stages 1, 9 and 12 (0.244094488188976377952755905512, 0.733846688281611857341361741547,
/// 0.220588235294117647058823529412e-1).
#[allow(clippy::excessive_precision)]
pub(super) const DOP853_ERROR_3: [f64; 12] = {
    let mut e = DOP853_WEIGHTS;
    e[0] -= 0.244094488188976377952755905512;
    e[8] -= 0.733846688281611857341361741547;
    e[11] -= 0.220588235294117647058823529412e-1;
    e
};

/// The stages of all of DOP853's steps and of its continuous extension.
pub(super) const DOP853_EXTENDED_STAGES: usize = 16;

/// The four stages the continuous extension adds, with their rows over the 16 stages and their nodes: the first is
/// at the step's end (before any projection), the others at 0.1, 0.2 and 7/9 of the step.
#[allow(clippy::excessive_precision)]
pub(super) const DOP853_EXTENSION: [([f64; DOP853_EXTENDED_STAGES], f64); 4] = [
    (row(&DOP853_WEIGHTS), 1.0),
    (
        row(&[
            5.61675022830479523392909219681e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            2.53500210216624811088794765333e-1,
            -2.46239037470802489917441475441e-1,
            -1.24191423263816360469010140626e-1,
            1.5329179827876569731206322685e-1,
            8.20105229563468988491666602057e-3,
            7.56789766054569976138603589584e-3,
            -8.298e-3,
        ]),
        0.1,
    ),
    (
        row(&[
            3.18346481635021405060768473261e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            2.83009096723667755288322961402e-2,
            5.35419883074385676223797384372e-2,
            -5.49237485713909884646569340306e-2,
            0.0,
            0.0,
            -1.08347328697249322858509316994e-4,
            3.82571090835658412954920192323e-4,
            -3.40465008687404560802977114492e-4,
            1.41312443674632500278074618366e-1,
        ]),
        0.2,
    ),
    (
        row(&[
            -4.28896301583791923408573538692e-1,
            0.0,
            0.0,
            0.0,
            0.0,
            -4.69762141536116384314449447206,
            7.68342119606259904184240953878,
            4.06898981839711007970213554331,
            3.56727187455281109270669543021e-1,
            0.0,
            0.0,
            0.0,
            -1.39902416515901462129418009734e-3,
            2.9475147891527723389556272149,
            -9.15095847217987001081870187138,
        ]),
        7.0 / 9.0,
    ),
];

/// The continuous extension's last four coefficient rows, over the 16 stages (Hairer's `d` coefficients; see
/// [`dop853_dense_weights`]).
#[allow(clippy::excessive_precision)]
pub(super) const DOP853_DENSE: [[f64; DOP853_EXTENDED_STAGES]; 4] = [
    [
        -0.84289382761090128651353491142e1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.56671495351937776962531783590,
        -0.30689499459498916912797304727e1,
        0.23846676565120698287728149680e1,
        0.21170345824450282767155149946e1,
        -0.87139158377797299206789907490,
        0.22404374302607882758541771650e1,
        0.63157877876946881815570249290,
        -0.88990336451333310820698117400e-1,
        0.18148505520854727256656404962e2,
        -0.91946323924783554000451984436e1,
        -0.44360363875948939664310572000e1,
    ],
    [
        0.10427508642579134603413151009e2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.24228349177525818288430175319e3,
        0.16520045171727028198505394887e3,
        -0.37454675472269020279518312152e3,
        -0.22113666853125306036270938578e2,
        0.77334326684722638389603898808e1,
        -0.30674084731089398182061213626e2,
        -0.93321305264302278729567221706e1,
        0.15697238121770843886131091075e2,
        -0.31139403219565177677282850411e2,
        -0.93529243588444783865713862664e1,
        0.35816841486394083752465898540e2,
    ],
    [
        0.19985053242002433820987653617e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.38703730874935176555105901742e3,
        -0.18917813819516756882830838328e3,
        0.52780815920542364900561016686e3,
        -0.11573902539959630126141871134e2,
        0.68812326946963000169666922661e1,
        -0.10006050966910838403183860980e1,
        0.77771377980534432092869265740,
        -0.27782057523535084065932004339e1,
        -0.60196695231264120758267380846e2,
        0.84320405506677161018159903784e2,
        0.11992291136182789328035130030e2,
    ],
    [
        -0.25693933462703749003312586129e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.15418974869023643374053993627e3,
        -0.23152937917604549567536039109e3,
        0.35763911791061412378285349910e3,
        0.93405324183624310003907691704e2,
        -0.37458323136451633156875139351e2,
        0.10409964950896230045147246184e3,
        0.29840293426660503123344363579e2,
        -0.43533456590011143754432175058e2,
        0.96324553959188282948394950600e2,
        -0.39177261675615439165231486172e2,
        -0.14972683625798562581422125276e3,
    ],
];

/// The dense-output weights of DOP853 over its 16 stages at the fraction `theta` of the step, from Hairer's
/// form of the order-7 extension, `y(θ) = y₀ + θ(r₂ + θ'(r₃ + θ(r₄ + θ'(r₅ + θ(r₆ + θ'(r₇ + θr₈))))))` with
/// `θ' = 1 − θ`: `r₂` the step's increment `Σ bᵢKᵢ`, `r₃ = K₁ − r₂`, `r₄ = r₂ − K₁₃ − r₃` (K₁₃ the slope at the
/// step's end), `r₅…r₈` the rows of [`DOP853_DENSE`]. Every `r` is linear in the stages, so the extension is a set of
/// weights, the increment's at θ = 1.
pub(super) fn dop853_dense_weights(theta: f64) -> [f64; DOP853_EXTENDED_STAGES] {
    let increment: [f64; DOP853_EXTENDED_STAGES] = row(&DOP853_WEIGHTS);
    let unit = |i: usize| -> [f64; DOP853_EXTENDED_STAGES] { std::array::from_fn(|j| if j == i { 1.0 } else { 0.0 }) };
    let (first, end) = (unit(0), unit(DOP853.b.len()));
    let r3: [f64; DOP853_EXTENDED_STAGES] = std::array::from_fn(|j| first[j] - increment[j]);
    let r4: [f64; DOP853_EXTENDED_STAGES] = std::array::from_fn(|j| increment[j] - end[j] - r3[j]);
    let after = 1.0 - theta;
    let [r5, r6, r7, r8] = DOP853_DENSE;
    std::array::from_fn(|j| {
        let inner = r5[j] + theta * (r6[j] + after * (r7[j] + theta * r8[j]));
        theta * (increment[j] + after * (r3[j] + theta * (r4[j] + after * inner)))
    })
}

/// A row of a strictly lower triangular tableau: its leading entries, then zeros.
pub(super) const fn row<const S: usize>(leading: &[f64]) -> [f64; S] {
    let mut row = [0.0; S];
    let mut j = 0;
    while j < leading.len() {
        row[j] = leading[j];
        j += 1;
    }
    row
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every rooted tree with at most `max_order` vertices, as the list of its root's subtrees (indices of
    /// earlier trees, non-decreasing), with its order.
    fn rooted_trees(max_order: usize) -> Vec<(Vec<usize>, usize)> {
        let mut trees: Vec<(Vec<usize>, usize)> = vec![(Vec::new(), 1)];
        for order in 2..=max_order {
            // Multisets of earlier trees whose orders sum to order − 1, built with non-decreasing indices.
            let mut stack: Vec<(Vec<usize>, usize)> = vec![(Vec::new(), 0)];
            let existing = trees.len();
            while let Some((children, size)) = stack.pop() {
                if size == order - 1 {
                    trees.push((children, order));
                    continue;
                }
                let from = children.last().copied().unwrap_or(0);
                for (index, (_, child_order)) in trees.iter().enumerate().take(existing).skip(from) {
                    if size + child_order < order {
                        let mut next = children.clone();
                        next.push(index);
                        stack.push((next, size + child_order));
                    }
                }
            }
        }
        trees
    }

    /// The order conditions `Σ bᵢ Φᵢ(τ) = 1/γ(τ)` for every tree τ up to the tableau's order (Butcher), where
    /// `Φᵢ(τ) = Πₖ Σⱼ aᵢⱼ Φⱼ(τₖ)` over the root's subtrees τₖ and `γ(τ) = |τ| Πₖ γ(τₖ)`.
    fn order_condition_defects<const S: usize>(tableau: &Tableau<S>, theta: f64) -> Vec<f64> {
        let trees = rooted_trees(tableau.order as usize);
        let mut weights: Vec<[f64; S]> = Vec::new();
        let mut densities: Vec<f64> = Vec::new();
        for (children, order) in &trees {
            let mut phi = [1.0; S];
            let mut gamma = *order as f64;
            for &child in children {
                for (i, p) in phi.iter_mut().enumerate() {
                    *p *= (0..S).map(|j| tableau.a[i][j] * weights[child][j]).sum::<f64>();
                }
                gamma *= densities[child];
            }
            weights.push(phi);
            densities.push(gamma);
        }
        weights
            .iter()
            .zip(&densities)
            .zip(&trees)
            .map(|((phi, gamma), (_, order))| {
                ((0..S).map(|i| tableau.b[i] * phi[i]).sum::<f64>() - theta.powi(*order as i32) / gamma).abs()
            })
            .collect()
    }

    #[test]
    fn rooted_trees_are_counted_right() {
        // 1, 1, 2, 4, 9, 20 trees of orders 1..6 (OEIS A000081).
        let trees = rooted_trees(6);
        let counts: Vec<usize> = (1..=6).map(|n| trees.iter().filter(|t| t.1 == n).count()).collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20]);
    }

    #[test]
    fn cooper_verner_8_satisfies_the_order_conditions() {
        assert_eq!(SQRT_21 * SQRT_21, 21.0);
        for (i, row) in COOPER_VERNER_8.a.iter().enumerate() {
            let sum = row.iter().sum::<f64>();
            assert!(
                (sum - COOPER_VERNER_8.c[i]).abs() < 1e-14,
                "c{i} is not the row sum: {sum}"
            );
        }
        let defects = order_condition_defects(&COOPER_VERNER_8, 1.0);
        assert_eq!(defects.len(), 200);
        let worst = defects.iter().copied().fold(0.0, f64::max);
        assert!(worst < 1e-13, "largest order-condition defect {worst:e}");
        let ninth = Tableau {
            order: 9,
            ..COOPER_VERNER_8
        };
        assert!(order_condition_defects(&ninth, 1.0).iter().any(|&d| d > 1e-6));
    }

    #[test]
    fn butcher_6_satisfies_the_order_conditions() {
        for (i, row) in BUTCHER_6.a.iter().enumerate() {
            assert!(
                (row.iter().sum::<f64>() - BUTCHER_6.c[i]).abs() < 1e-15,
                "c{i} is not the row sum"
            );
        }
        let defects = order_condition_defects(&BUTCHER_6, 1.0);
        assert_eq!(defects.len(), 37);
        let worst = defects.iter().copied().fold(0.0, f64::max);
        assert!(worst < 1e-15, "largest order-condition defect {worst:e}");
        // And it is not of order 7: some order-7 condition fails.
        let seventh = Tableau { order: 7, ..BUTCHER_6 };
        assert!(order_condition_defects(&seventh, 1.0).iter().any(|&d| d > 1e-6));
    }

    #[test]
    fn dormand_prince_5_satisfies_the_order_conditions() {
        let pair = &DORMAND_PRINCE_5;
        for (i, row) in pair.a.iter().enumerate() {
            assert!(
                (row.iter().sum::<f64>() - pair.c[i]).abs() < 1e-14,
                "c{i} is not the row sum"
            );
        }
        let worst = |defects: Vec<f64>| defects.iter().copied().fold(0.0, f64::max);
        let defects = order_condition_defects(pair, 1.0);
        assert_eq!(defects.len(), 17);
        assert!(worst(defects) < 1e-14);
        assert!(order_condition_defects(&Tableau { order: 6, ..*pair }, 1.0)
            .iter()
            .any(|&d| d > 1e-6));
        // The embedded solution, b̂ = b − e: order 4, not 5.
        let embedded = Tableau {
            b: std::array::from_fn(|i| pair.b[i] - DORMAND_PRINCE_5_ERROR[i]),
            order: 4,
            ..*pair
        };
        assert!(worst(order_condition_defects(&embedded, 1.0)) < 1e-14);
        assert!(order_condition_defects(&Tableau { order: 5, ..embedded }, 1.0)
            .iter()
            .any(|&d| d > 1e-6));
        // The continuous extension: order 4 at every fraction of the step, the kept solution at its end.
        for theta in [0.1, 1.0 / 3.0, 0.5, 0.8, 1.0] {
            let dense = Tableau {
                b: dormand_prince_5_dense_weights(theta),
                order: 4,
                ..*pair
            };
            assert!(worst(order_condition_defects(&dense, theta)) < 1e-14, "θ = {theta}");
        }
        let at_end = dormand_prince_5_dense_weights(1.0);
        assert!(at_end.iter().zip(&pair.b).all(|(d, b)| (d - b).abs() < 1e-15));
    }

    #[test]
    fn dop853_satisfies_the_order_conditions() {
        let worst = |defects: Vec<f64>| defects.iter().copied().fold(0.0, f64::max);
        let pair = &DOP853;
        for (i, row) in pair.a.iter().enumerate() {
            let sum = row.iter().sum::<f64>();
            assert!((sum - pair.c[i]).abs() < 1e-14, "c{i} is not the row sum: {sum}");
        }
        let defects = order_condition_defects(pair, 1.0);
        assert_eq!(defects.len(), 200);
        assert!(worst(defects) < 1e-13);
        assert!(order_condition_defects(&Tableau { order: 9, ..*pair }, 1.0)
            .iter()
            .any(|&d| d > 1e-6));
        // The embedded solutions b̂ = b − e: orders 5 and 3, not higher.
        for (error, order) in [(&DOP853_ERROR_5, 5), (&DOP853_ERROR_3, 3)] {
            let embedded = Tableau {
                b: std::array::from_fn(|i| pair.b[i] - error[i]),
                order,
                ..*pair
            };
            assert!(worst(order_condition_defects(&embedded, 1.0)) < 1e-13, "order {order}");
            assert!(order_condition_defects(
                &Tableau {
                    order: order + 1,
                    ..embedded
                },
                1.0
            )
            .iter()
            .any(|&d| d > 1e-6));
        }
        // The extension's stages on top of the step's, and the continuous extension: order 7 at every fraction of
        // the step, the kept solution at its end.
        let mut a = [[0.0; DOP853_EXTENDED_STAGES]; DOP853_EXTENDED_STAGES];
        let mut c = [0.0; DOP853_EXTENDED_STAGES];
        for (i, step_row) in pair.a.iter().enumerate() {
            a[i] = row(step_row);
            c[i] = pair.c[i];
        }
        for (k, (extension_row, node)) in DOP853_EXTENSION.iter().enumerate() {
            let i = pair.b.len() + k;
            (a[i], c[i]) = (*extension_row, *node);
            let sum = extension_row.iter().sum::<f64>();
            assert!((sum - node).abs() < 1e-14, "c{i} is not the row sum");
        }
        for theta in [0.1, 1.0 / 3.0, 0.5, 0.8, 1.0] {
            let dense = Tableau {
                a,
                b: dop853_dense_weights(theta),
                c,
                order: 7,
            };
            assert!(worst(order_condition_defects(&dense, theta)) < 1e-13, "θ = {theta}");
            // Inside the step it is of order 7 only (at its end it is the 8th-order solution).
            let eighth = Tableau { order: 8, ..dense };
            let defects = order_condition_defects(&eighth, theta);
            assert!(theta == 1.0 || defects.iter().any(|&d| d > 1e-9), "θ = {theta}");
        }
        let at_end = dop853_dense_weights(1.0);
        assert!(at_end
            .iter()
            .zip(&row::<DOP853_EXTENDED_STAGES>(&pair.b))
            .all(|(d, b)| (d - b).abs() < 1e-15));
    }
}
